"""Sphinx configuration of the trackcert documentation site.

Build it with ``sphinx-build -W --keep-going -b html docs docs/_build/html`` after
``pip install '.[docs]'``: the Markdown pages are parsed by MyST, the tutorials (MyST text
notebooks in ``tutorials/``) are executed against the installed package, and the API reference
is generated from the numpydoc docstrings of ``trackcert``.
"""

import os

import trackcert

project = "trackcert"
author = "the trackcert authors"
copyright = "trackcert authors"
release = version = trackcert.__version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
]
exclude_patterns = ["_build", "examples", "**/.ipynb_checkpoints", "jupyter_execute"]
# Code samples that elide with "…" are still highlighted (Pygments retries in relaxed mode).
suppress_warnings = ["misc.highlighting_failure"]

# MyST: the Markdown pages and the notebooks
myst_enable_extensions = ["colon_fence", "dollarmath", "deflist"]
myst_heading_anchors = 3
nb_execution_mode = "force"
nb_execution_timeout = 300
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_merge_streams = True

# the API reference
autosummary_generate = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # the numpydoc sections state the types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

html_theme = "furo"
html_title = f"trackcert {release}"
html_static_path: list[str] = []

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # the notebooks' kernels inherit it
os.environ.setdefault("OMP_NUM_THREADS", "1")
