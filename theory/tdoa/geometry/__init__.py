"""The geometry seen from the target (seed 000 §4.2.1, §4.3.1): :mod:`.exact` (exact ranks and
mirror images on the coordinates as written), :mod:`.directions` (when the stacked Jacobian loses
rank), :mod:`.uniqueness` (every position with the same TDOAs), :mod:`.crb` (Cramér–Rao bounds
and optimal formations), :mod:`.margin` (how far agents may drift, certified), :mod:`.placement`
(formations of least Cramér–Rao trace with a certified margin)."""
