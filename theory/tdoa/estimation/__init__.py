"""Estimating and tracking the target (seed 000 §4.2–4.4, App. A–B): :mod:`.filters` (EKF steps,
averaging, the network filters), :mod:`.averaged` (mean-square bounds of the averaged filter),
:mod:`.stability` (App. A), :mod:`.agents` (steering robots and formations), :mod:`.scenario`
(one closed loop), :mod:`.simulation` (``trackcert simulate`` on ``kind: tdoa-sim``)."""
