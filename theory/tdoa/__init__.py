"""TDOA-based distributed localization of a moving target (seed 000 ch. 4, App. A–B; seed 001).

:mod:`~theory.tdoa.case` (the ``tdoa`` and ``tdoa-sim`` case kinds), :mod:`~theory.tdoa.model`
(the target and its TDOA measurements), :mod:`~theory.tdoa.geometry` (what the directions from the
target decide: exact ranks, uniqueness, Cramér–Rao bounds, displacement margins, placement),
:mod:`~theory.tdoa.design` (redundancy and the design summary), :mod:`~theory.tdoa.observability`
(one agent, the networked pair, the topology verdicts, their certificates and properties),
:mod:`~theory.tdoa.estimation` (the network filters, their closed loop and App. A's stability),
:mod:`~theory.tdoa.strategies` (public hypothesis strategies) and :mod:`~theory.tdoa.registry`.
"""
