"""Closed-loop simulation of distributed TDOA localization and pursuit (seed 000 §4.3–4.4).

One module per idea: :mod:`targets` (the constant-velocity target), :mod:`measurements` (TDOA),
:mod:`ekf` (extended Kalman updates), :mod:`consensus` (averaging of estimates and covariances),
:mod:`filters` (averaged / decentralized / centralized network filters), :mod:`formation`
(desired offsets), :mod:`agents` (3D steering robots with dynamic feedback linearization),
:mod:`scenario` (one closed-loop run), :mod:`metrics`, :mod:`runner` (Monte Carlo),
:mod:`figures`, :mod:`outputs`, :mod:`crb` (static CRB and posterior CRB), :mod:`consensus_kf`
(seed 000 ch. 5), :mod:`appendix_a` (Lemma A.1.2 along runs), :mod:`range_dekf` (seed 003's
information-form DEKF), :mod:`pursuit` (seed 003's 2-D DEC loop),
:mod:`pursuit_sim` (``simulate`` for pursuit cases), :mod:`iss_check` (Theorem 2 along runs),
:mod:`sim_claims`
(registered claims) and :mod:`tdoa_sim_case` (the ``kind: tdoa-sim`` case block).
"""
