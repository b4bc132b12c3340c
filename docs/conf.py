# Sphinx configuration of the reference documentation: the Markdown pages of docs/ (MyST) and the
# Python API generated from the package's docstrings. Built with warnings as errors by ctest
# `docs_build` (a broken cross-reference, a missing image or a docstring that does not parse
# fails it):
#   ASPERITY_PYTHONPATH=$PWD/build/python sphinx-build -W -b html docs build/docs-html
import os
import sys

# The built package: autodoc imports it to read its docstrings. ASPERITY_PYTHONPATH (absolute: Sphinx
# reads this file from docs/), else the build folder beside docs/.
here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.environ.get("ASPERITY_PYTHONPATH", os.path.join(here, "..", "build", "python")))

project = "asperity"
extensions = ["myst_parser", "sphinx.ext.autodoc"]
source_suffix = {".md": "markdown"}
root_doc = "index"
myst_heading_anchors = 4  # the pages link to sections by GitHub's anchors (#the-recovery-matrix)
autodoc_member_order = "bysource"
html_theme = "alabaster"
