# Sphinx configuration of whirl's manual (make docs: HTML into build/docs/, warnings are errors).
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(HERE, "_ext"))
sys.path.insert(0, os.path.join(ROOT, "python"))


def _version():
    parts = {}
    with open(os.path.join(ROOT, "include", "whirl", "version.h")) as f:
        for m in re.finditer(r"#define WHIRL_VERSION_(MAJOR|MINOR|PATCH) (\d+)", f.read()):
            parts[m.group(1)] = m.group(2)
    return "%s.%s.%s" % (parts["MAJOR"], parts["MINOR"], parts["PATCH"])


project = "whirl"
author = "the whirl developers"
copyright = "the whirl developers, GPL-3.0-or-later"
release = version = _version()

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax", "whirl_capi", "whirl_pydoc", "whirl_text"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "README.md"]
root_doc = "index"
html_theme = "alabaster"
html_static_path = ["_static"]
html_title = "whirl %s" % release
html_theme_options = {"page_width": "1200px", "sidebar_width": "240px"}
# The C API (api/c.rst) is generated from include/whirl/*.h by _ext/whirl_capi.py.
whirl_include_dir = os.path.join(ROOT, "include")
primary_domain = "c"
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "undoc-members": False}
# The equations are typeset by MathJax when a page is viewed: Debian's copy (libjs-mathjax), so that
# the manual reads offline; without it, MathJax's CDN. The build itself needs no network.
_MATHJAX = "/usr/share/javascript/mathjax/MathJax.js"
if os.path.exists(_MATHJAX):
    mathjax_path = "file://" + _MATHJAX + "?config=TeX-AMS-MML_HTMLorMML"
    # MathJax 2: typeset the math nodes Sphinx writes, whatever class MyST gives the page
    myst_update_mathjax = False
    mathjax2_config = {"tex2jax": {"processClass": "math", "ignoreClass": "document",
                                   "inlineMath": [["\\(", "\\)"]],
                                   "displayMath": [["\\[", "\\]"]]}}
html_css_files = ["whirl.css"]
# The live page of `make web` (whirl-explore.html in the web/ folder beside the library the
# manual documents, or WHIRL_EXPLORE_PAGE), embedded in guide/explore.md when it is built: copied
# into the manual's _static, and the tag whirl_web set; without it the guide says how to get it.
_LIBRARY = os.environ.get("WHIRL_LIBRARY", os.path.join(ROOT, "build", "libwhirl.so"))
_PAGE = os.environ.get("WHIRL_EXPLORE_PAGE") or os.path.join(os.path.dirname(_LIBRARY), "web",
                                                             "whirl-explore.html")
if os.path.isfile(_PAGE):
    html_static_path.append(os.path.abspath(_PAGE))
    tags.add("whirl_web")  # noqa: F821 (Sphinx puts tags in this file's namespace)
