"""The closed-loop simulation engine: Monte Carlo over seeds, data files and figures.

It holds no model: every system's dynamics, measurements and filters live in its domain package.
"""
