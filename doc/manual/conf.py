# Sphinx configuration of the dualcontact manual (Markdown through MyST).
# Built by scripts/docs (warnings are errors); Debian's python3-sphinx and
# python3-myst-parser (scripts/setup --docs installs them).
import os

project = "dualcontact"
author = "the dualcontact authors"
copyright = "2026, " + author
extensions = ["myst_parser"]
source_suffix = {".md": "markdown"}
master_doc = "index"
exclude_patterns = ["_build"]
# `[text](page.md#a-heading)' links to headings up to this level
myst_heading_anchors = 3
html_theme = "alabaster"
html_static_path = []
html_show_sourcelink = False

_manual = os.path.dirname(os.path.abspath(__file__))
_repository = os.path.dirname(os.path.dirname(_manual))


def _link_to_repository_file(app, env, node, contnode):
    """A Markdown link from the manual to a file of the repository outside
    it (a benchmark report, tests/README.md, an input): a link to that file
    from the HTML page, so that it works on GitHub and in the HTML alike.
    A link to a file that does not exist stays a warning (an error under
    scripts/docs)."""
    from docutils import nodes

    target = node.get("reftarget", "")
    if "://" in target or target.startswith("#"):
        return None
    path = target.split("#", 1)[0]
    if not path:
        return None
    source_dir = os.path.dirname(env.doc2path(node.get("refdoc", env.docname)))
    absolute = os.path.normpath(os.path.join(source_dir, path))
    if not absolute.startswith(_repository + os.sep) or absolute.startswith(
        _manual + os.sep
    ):
        return None
    if not os.path.exists(absolute):
        return None
    page_dir = os.path.dirname(
        os.path.join(app.outdir, node.get("refdoc", env.docname))
    )
    uri = os.path.relpath(absolute, page_dir)
    reference = nodes.reference("", "", internal=False, refuri=uri)
    reference.append(contnode)
    return reference


def setup(app):
    app.connect("missing-reference", _link_to_repository_file)
