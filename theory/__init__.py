"""trackcert's library: models, observability, detectability, LMIs, ISS, simulation.

See ``docs/modules.md`` for a map of modules to the concepts of the papers.
"""

__version__ = "0.1.0"
