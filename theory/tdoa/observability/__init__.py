"""Observability of TDOA localization (seed 000 §4.2; seed 001): :mod:`.single_agent` (every
minor of one agent's O), :mod:`.window` (over a window of pings), :mod:`.weights` (Metropolis
weights, Lemma 4.2.2), :mod:`.network` (the networked pair), :mod:`.spectral` (its rank from the
spectrum of W), :mod:`.fig43` (Thm 4.2.3), :mod:`.topology` (every agent's verdict),
:mod:`.trajectory` (along time steps; ``trackcert topology``), :mod:`.certificates` (generic-rank
certificates), :mod:`.properties` (falsifiable wordings)."""
