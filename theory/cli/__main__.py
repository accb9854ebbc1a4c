"""``python -m theory.cli``: the same as the ``trackcert`` console script."""

from theory.cli import main

main()
