"""The C API reference, generated from the public headers include/whirl/*.h.

`.. whirl-c-header:: whirl/steady.h` reads the header and writes Sphinx's C domain directives for
everything it declares: each macro (#define), function (WHIRL_API ...;), struct with its members,
opaque type, enum with its enumerators and function-pointer type, with the comment that precedes
it (or follows it on the same line) as its description. The header's opening comment becomes the
section's introduction. In a function's comment the lines "@param NAME text", "@return text" and
"@retval STATUS text" (each continued on the lines below it up to a blank line or the next "@")
become its lists of parameters, return value and statuses; a NAME that is not one of the
function's parameters stops the build. Nothing is written by hand, so a new public function is in the reference
as soon as it is in a header; tests/cli/test_docs.sh checks that every symbol the shared library
exports has its entry.
"""
import os
import re

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.errors import ExtensionError

from whirl_text import SourceDirective


def _tokens(text):
    """The header as (kind, text, first line, last line): kind 'comment', 'pp' or 'decl'
    (a declaration up to its ';' at brace depth 0)."""
    out = []
    i, n, line = 0, len(text), 1
    decl, decl_line, depth = [], None, 0
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.index("*/", i) + 2
            body = text[i:j]
            if depth == 0 and not "".join(decl).strip():
                out.append(("comment", body, line, line + body.count("\n")))
            else:
                decl.append(body)
            line += body.count("\n")
            i = j
            continue
        if c == "#" and not "".join(decl).strip():
            j = i
            while True:
                k = text.find("\n", j)
                k = n if k < 0 else k
                if k > 0 and text[k - 1] == "\\":
                    j = k + 1
                    continue
                break
            body = text[i:k]
            # a comment after the directive on its line is kept apart
            m = re.search(r"/\*.*?\*/\s*$", body)
            if m and not body.startswith("#if"):
                out.append(("pp", body[:m.start()].rstrip(), line, line + body.count("\n")))
                out.append(("comment", m.group(0), line + body.count("\n"),
                            line + body.count("\n")))
            else:
                out.append(("pp", body, line, line + body.count("\n")))
            line += body.count("\n")
            i = k
            continue
        if c == "\n":
            line += 1
        if not decl and c.isspace():
            i += 1
            continue
        if not decl:
            decl_line = line
        decl.append(c)
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
        elif c == ";" and depth == 0:
            out.append(("decl", "".join(decl), decl_line, line))
            decl = []
        i += 1
    return out


def _comment_text(body):
    """The text of a C comment: delimiters and the leading ' * ' of each line removed."""
    body = body.strip()
    body = body[2:-2] if body.startswith("/*") else body
    lines = []
    for ln in body.split("\n"):
        ln = re.sub(r"^\s*\*(?!/)\s?", "", ln) if ln.lstrip().startswith("*") else ln.strip()
        lines.append(ln.rstrip())
    while lines and not lines[0].strip():
        lines.pop(0)
    while lines and not lines[-1].strip():
        lines.pop()
    return lines


def _escape(s):
    return re.sub(r"([\\*`_|])", r"\\\1", s)


def _rst_text(lines, indent):
    """Comment lines as reStructuredText: paragraphs of escaped text; a line beginning with '-'
    or indented more than the paragraph's first line starts a new paragraph, so that lists and
    examples keep their lines."""
    pad = " " * indent
    out, para = [], []

    def flush():
        if para:
            out.append(pad + " ".join(_escape(p.strip()) for p in para))
            out.append("")
            para.clear()

    base = None
    for ln in lines:
        if not ln.strip():
            flush()
            base = None
            continue
        ind = len(ln) - len(ln.lstrip())
        if para and (ln.lstrip().startswith("- ") or (base is not None and ind > base + 1)):
            flush()
        if not para:
            base = ind
        para.append(ln)
    flush()
    return out


_FIELD = re.compile(r"^@(param|return|returns|retval)\b\s*(.*)$")


def _split_fields(lines):
    """A comment's lines as (description lines, fields): each field [kind, name, text lines] from
    a line "@param NAME text", "@return text" or "@retval STATUS text" and the lines after it up
    to a blank line or the next field; lines after a field's blank line are description again."""
    body, fields, open_field = [], [], False
    for ln in lines:
        m = _FIELD.match(ln.strip())
        if m:
            kind, rest = m.group(1), m.group(2)
            name = ""
            if kind in ("param", "retval"):
                name, _, rest = rest.partition(" ")
            fields.append([kind, name, [rest.strip()]])
            open_field = True
        elif open_field and ln.strip():
            fields[-1][2].append(ln.strip())
        else:
            open_field = False
            body.append(ln)
    return body, fields


def _param_names(decl):
    """The parameter names of a function declaration (its last identifier in each comma-separated
    part between the outer parentheses; none for (void))."""
    inside = decl[decl.index("(") + 1:decl.rindex(")")]
    names, depth, part = [], 0, ""
    for c in inside + ",":
        if c == "," and depth == 0:
            m = re.search(r"(\w+)\s*(\[[^\]]*\])*\s*$", part) if "(" not in part else \
                re.search(r"\(\s*\*\s*(\w+)\s*\)", part)
            if m and part.strip() != "void":
                names.append(m.group(1))
            part = ""
            continue
        depth += c in "(["
        depth -= c in ")]"
        part += c
    return names


def _rst_fields(fields, indent):
    pad = " " * indent
    out = []
    for kind, name, text in fields:
        words = " ".join(_escape(t) for t in text if t)
        if kind == "param":
            out.append("%s:param %s: %s" % (pad, name, words))
        elif kind == "retval":
            out.append("%s:retval %s: %s" % (pad, name, words))
        else:
            out.append("%s:returns: %s" % (pad, words))
    return out + [""] if out else []


def _squash(s):
    s = re.sub(r"/\*.*?\*/", " ", s, flags=re.S)
    return re.sub(r"\s+", " ", s).strip()


def _members(body):
    """The members of a struct body (between its braces): (declaration, comment lines)."""
    toks = _tokens(body)
    members, pending = [], []
    for idx, (kind, text, first, last) in enumerate(toks):
        if kind == "comment":
            prev = toks[idx - 1] if idx else None
            if prev and prev[0] == "decl" and prev[3] == first and members:
                members[-1][1].extend(_comment_text(text))
            else:
                pending = _comment_text(text)
        elif kind == "decl":
            decl = _squash(text.rstrip(";"))
            # trailing comments inside the declaration (a comment between lines of it)
            inner = [_comment_text(c) for c in re.findall(r"/\*.*?\*/", text, flags=re.S)]
            doc = pending + [ln for c in inner for ln in c]
            members.append((decl, doc))
            pending = []
    out = []
    for decl, doc in members:
        if "(" in decl:  # a function pointer
            out.append((decl, doc))
            continue
        m = re.match(r"^(.*?)([A-Za-z_]\w*(\s*\[[^\]]*\])?)\s*((,\s*\**\s*[A-Za-z_]\w*(\s*\[[^\]]*\])?)*)$",
                     decl)
        if not m:
            out.append((decl, doc))
            continue
        typ, first = m.group(1).strip(), m.group(2)
        rest = [r.strip() for r in m.group(4).split(",") if r.strip()] if m.group(4) else []
        names = [first] + rest
        for name in names:
            stars = re.match(r"^\s*(\**)", name).group(1)
            out.append(("%s %s%s" % (typ.rstrip("*").rstrip() + (" " + typ[len(typ.rstrip("*")):]
                                                                if typ.endswith("*") else ""),
                                   stars, name.lstrip("* ")), doc))
    return out


class WhirlCHeader(SourceDirective):
    def run(self):
        path = os.path.join(self.state.document.settings.env.config.whirl_include_dir,
                            self.arguments[0])
        text = self.read(path)
        rst = self.header_rst(self.arguments[0], text)
        node = nodes.section()
        node.document = self.state.document
        self.state.nested_parse(StringList(rst, source=path), 0, node)
        return node.children

    @staticmethod
    def header_rst(name, text):
        # the extern "C" guards for C++ are no declarations
        text = re.sub(r'#ifdef __cplusplus\n(extern "C" \{|\})\n#endif\n', "\n", text)
        toks = _tokens(text)
        rst = []
        guard = None
        seen = set()
        pending = []
        intro_done = False
        for idx, (kind, body, first, last) in enumerate(toks):
            nxt = toks[idx + 1] if idx + 1 < len(toks) else None
            prev = toks[idx - 1] if idx else None
            if kind == "comment":
                lines = _comment_text(body)
                if not intro_done:
                    intro_done = True
                    rst += _rst_text(lines, 0)
                    continue
                if prev and prev[0] in ("decl", "pp") and prev[3] == first and rst \
                        and prev[0] != "comment":
                    # a comment on the line of the declaration before it: its description
                    rst += _rst_text(lines, 3)
                    continue
                if nxt and nxt[0] in ("decl", "pp") and nxt[2] == last + 1 \
                        and not (nxt[0] == "pp" and not nxt[1].startswith("#define")):
                    pending = lines
                else:
                    # a comment that stands alone: the introduction of what follows; a first
                    # line "---- title ----" is the title of a group of declarations
                    m = re.match(r"^\s*-{2,}\s*(.*?)\s*-{2,}\s*$", lines[0]) if lines else None
                    if m:
                        rst += [".. rubric:: " + _escape(m.group(1)), ""]
                        lines = lines[1:]
                    rst += _rst_text(lines, 0)
                    pending = []
                continue
            intro_done = True
            if kind == "pp":
                m = re.match(r"#\s*define\s+(\w+)(\([^)]*\))?\s*(.*)$", body, flags=re.S)
                if body.startswith("#ifndef") and guard is None:
                    guard = body.split()[1]
                if not m or m.group(1) == guard or m.group(1) in seen:
                    pending = []
                    continue
                seen.add(m.group(1))
                mname, args, value = m.group(1), m.group(2) or "", _squash(
                    body[m.end(2) if m.group(2) else m.end(1):].replace("\\\n", " "))
                rst += [".. c:macro:: %s%s" % (mname, args), ""]
                if value:
                    rst += ["   ``%s``" % value.replace("``", "` `"), ""]
                rst += _rst_text(pending, 3)
                pending = []
                continue
            decl = body
            inner_doc = []
            s = _squash(decl.rstrip(";"))
            s = s.replace("WHIRL_API ", "")
            # typedef struct X {...} X;  typedef enum [X] {...} Y;
            m = re.match(r"typedef\s+(struct|enum)\s*(\w*)\s*\{(.*)\}\s*(\w+)\s*;?\s*$",
                         decl.replace("WHIRL_API ", ""), flags=re.S)
            if m:
                what, tag, inside, tname = m.groups()
                if what == "struct":
                    rst += [".. c:struct:: %s" % tname, ""]
                    rst += _rst_text(pending + inner_doc, 3)
                    for mdecl, mdoc in _members(inside):
                        if "{" in mdecl:
                            # a member of an anonymous struct or union type: shown as declared
                            rst += ["   Member ``%s``:" % mdecl.replace("``", "` `"), ""]
                            rst += _rst_text(mdoc, 3)
                            continue
                        rst += ["   .. c:member:: %s" % mdecl, ""]
                        rst += _rst_text(mdoc, 6)
                else:
                    rst += [".. c:enum:: %s" % tname, ""]
                    rst += _rst_text(pending, 3)
                    for item, idoc in _enumerators(inside):
                        rst += ["   .. c:enumerator:: %s" % item, ""]
                        rst += _rst_text(idoc, 6)
                pending = []
                continue
            m = re.match(r"typedef\s+struct\s+(\w+)\s+(\w+)$", s)
            if m:
                rst += [".. c:struct:: %s" % m.group(2), ""]
                rst += _rst_text(pending, 3)
                pending = []
                continue
            if s.startswith("typedef"):
                rst += [".. c:type:: %s" % s[len("typedef"):].strip(), ""]
                rst += _rst_text(pending, 3)
                pending = []
                continue
            if "(" in s:
                rst += [".. c:function:: %s" % s, ""]
                body, fields = _split_fields(pending)
                known = _param_names(s)
                for kind, pname, _ in fields:
                    if kind == "param" and pname not in known:
                        raise ExtensionError("%s: @param %s: %s has no such parameter (%s)"
                                             % (name, pname, s.split("(")[0].split()[-1],
                                                ", ".join(known)))
                rst += _rst_text(body, 3)
                rst += _rst_fields(fields, 3)
            else:
                rst += [".. c:var:: %s" % s, ""]
                rst += _rst_text(pending, 3)
            pending = []
        return rst


def _enumerators(inside):
    """The enumerators of an enum body: ('NAME = value' or 'NAME', comment lines)."""
    toks = []
    # split on commas at the top level, keeping the comments with the enumerator they follow
    parts = re.split(r"(/\*.*?\*/)|,", inside, flags=re.S)
    items, pending = [], []
    for p in parts:
        if p is None:
            continue
        if p.startswith("/*"):
            if items and not pending and not items[-1][2]:
                items[-1][1].extend(_comment_text(p))
            else:
                pending += _comment_text(p)
            continue
        if "\n" in p and items:
            items[-1][2] = True  # a line break ends the same-line comment of the item before
        name = _squash(p)
        if name:
            items.append([name, pending, "\n" in p.split(name)[-1] if name in p else False])
            pending = []
    for name, doc, _ in items:
        toks.append((name, doc))
    return toks


def setup(app):
    app.add_config_value("whirl_include_dir", "", "env")
    app.add_directive("whirl-c-header", WhirlCHeader)
    return {"version": "1", "parallel_read_safe": True}
