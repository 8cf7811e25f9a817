# Sphinx configuration of the attenuvis documentation (docs/CMakeLists.txt
# builds it; the README says how).  Pages are MyST Markdown.  Three inputs
# come from the build tree, passed as environment variables by CMake:
#   ATTENUVIS_CLI          the built program: the command-line reference and
#                          the man page are its own --help (one source of truth)
#   ATTENUVIS_DOXYGEN_XML  Doxygen's XML of the public headers (breathe)
#   PYTHONPATH             the build tree's Python package (autodoc)
# The site uses only files it ships (no fonts, scripts or math from the
# network), so the installed copy reads offline.
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "_ext"))

project = "attenuvis"
author = "the attenuvis authors"
copyright = "the attenuvis authors"
release = version = os.environ.get("ATTENUVIS_VERSION", "")

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "breathe",
    "attenuvis_docs",
]
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build", "README.md"]
root_doc = "index"
nitpicky = False
myst_heading_anchors = 3
myst_enable_extensions = ["colon_fence", "deflist"]

# Python reference (numpy-style docstrings).
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_type_aliases = {"ArrayLike": "numpy.typing.ArrayLike"}
autodoc_default_options = {"members": None}
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_ivar = True

# C++ reference from Doxygen's XML.
breathe_projects = {"attenuvis": os.environ.get("ATTENUVIS_DOXYGEN_XML", "")}
breathe_default_project = "attenuvis"
breathe_domain_by_extension = {"hpp": "cpp"}
breathe_show_include = True

# HTML: Sphinx's Alabaster theme as Debian ships it, without the parts that
# load badges or buttons from the network.
html_theme = "alabaster"
html_theme_options = {
    "description": "Lorenz–Mie scattering, weather optics and weather-weighted visibility graphs",
    "fixed_sidebar": False,
    "page_width": "1100px",
    "sidebar_width": "230px",
    "font_family": "system-ui, -apple-system, 'Segoe UI', 'DejaVu Sans', sans-serif",
    "head_font_family": "system-ui, -apple-system, 'Segoe UI', 'DejaVu Sans', sans-serif",
    "code_font_family": "'DejaVu Sans Mono', monospace",
    "show_relbars": True,
}
html_sidebars = {"**": ["about.html", "navigation.html", "relations.html", "searchbox.html"]}
html_static_path = ["_static"]
html_css_files = ["attenuvis.css"]
html_show_sourcelink = False
html_copy_source = False
html_title = "attenuvis"

# The man page attenuvis(1): the command-line reference rendered by the man builder.
man_pages = [("reference/man", "attenuvis", "Lorenz-Mie, weather optics and weather-weighted visibility graphs",
              [author], 1)]
man_show_urls = False
