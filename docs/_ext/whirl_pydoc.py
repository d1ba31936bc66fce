"""The Python package's docstrings are plain text (lines laid out for `help()`), not
reStructuredText: autodoc shows them as line blocks, each line as written, with ``literal`` spans
kept and every other markup character escaped, so that no docstring can break the build."""
import re


def _escape(s):
    parts = re.split(r"(``[^`]+``)", s)
    out = []
    for i, p in enumerate(parts):
        if i % 2:
            out.append(p)
        else:
            p = re.sub(r"([\\*`|])", r"\\\1", p)
            p = re.sub(r"_(?=\W|$)", r"\\_", p)
            out.append(p)
    return "".join(out)


def _line_block(app, what, name, obj, options, lines):
    if not lines:
        return
    body = [("| " + _escape(ln)) if ln.strip() else "|" for ln in lines]
    while body and body[-1] == "|":
        body.pop()
    lines[:] = body + [""]


def setup(app):
    app.connect("autodoc-process-docstring", _line_block)
    return {"version": "1", "parallel_read_safe": True}
