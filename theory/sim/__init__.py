"""Closed-loop simulation of distributed localization and pursuit (seed 000 ch. 4–5, seed 003).

One module per idea:

* seed 000 ch. 4 — :mod:`targets` (constant-velocity target), :mod:`measurements` (TDOA),
  :mod:`ekf`, :mod:`consensus` (averaging of estimates and covariances), :mod:`filters`
  (averaged / decentralized / centralized), :mod:`formation`, :mod:`agents` (3D steering robots
  with dynamic feedback linearization), :mod:`tdoa_sim_case` (``kind: tdoa-sim``),
  :mod:`scenario` (one closed-loop run), :mod:`metrics`, :mod:`outputs`, :mod:`figures`,
  :mod:`crb` (static CRB and posterior CRB), :mod:`appendix_a` (Lemma A.1.2 along runs);
* seed 000 ch. 5 — :mod:`consensus_kf` (both orders, exact error covariance), :mod:`dkf_sim`;
* seed 003 — :mod:`range_dekf` (information-form DEKF), :mod:`pursuit` (2-D DEC loop),
  :mod:`pursuit_sim`, :mod:`iss_check` (Theorem 2 along runs);
* shared — :mod:`runner` (Monte Carlo) and :mod:`sim_claims` (registered claims).
"""
