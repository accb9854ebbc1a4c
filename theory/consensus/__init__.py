"""Consensus-based distributed Kalman filtering (seed 000 ch. 5, App. A, C).

``case`` (the ``dkf`` kind, the filter :class:`~theory.consensus.case.Order`), ``operators``
(L, J and their exact radii), ``conditions`` (Thm 5.2.10 and the blind-set condition),
``s_detectability`` (the LMI decision), ``certificates`` and ``infeasibility`` (exact witnesses
both ways), ``riccati`` and ``kalman_filter`` (the filter and its covariances), ``analysis`` (a
case's one analysis, its claims and ``trackcert dkf``), ``suboptimal_gains`` (App. C.2),
``properties`` and ``strategies`` (for ``trackcert falsify`` and tests).
"""
