"""Text taken from the program and the sources when the manual is built, so that it cannot drift:

```{whirl-help} shape
```
    the output of `whirl shape --help` (the program of the build, WHIRL_PROGRAM or build/whirl);

```{whirl-opening} src/steady/continuum.c
```
    the opening comment of a source file (its equations and references), as preformatted text.
"""
import os
import re
import subprocess
import sys

from docutils import nodes
from docutils.parsers.rst import Directive
from sphinx.errors import ExtensionError


class SourceDirective(Directive):
    """A directive with one argument whose page is read again when a file it reads changes, or
    the extension that defines it."""
    required_arguments = 1
    has_content = False

    def note(self, path):
        env = self.state.document.settings.env
        env.note_dependency(path)
        env.note_dependency(sys.modules[type(self).__module__].__file__)
        return env

    def read(self, path):
        self.note(path)
        with open(path) as f:
            return f.read()


class WhirlHelp(SourceDirective):
    def run(self):
        prog = self.state.document.settings.env.config.whirl_program
        self.note(prog)  # the page is read again when the program changes
        p = subprocess.run([prog, self.arguments[0], "--help"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            raise ExtensionError("%s %s --help failed: %s" % (prog, self.arguments[0],
                                                             p.stderr.strip()))
        node = nodes.literal_block(p.stdout, p.stdout)
        node["language"] = "text"
        return [node]


class WhirlOpening(SourceDirective):
    def run(self):
        path = os.path.join(self.state.document.settings.env.config.whirl_root, self.arguments[0])
        m = re.match(r"\s*/\*(.*?)\*/", self.read(path), re.S)
        if not m:
            raise ExtensionError("%s does not open with a comment" % path)
        lines = [re.sub(r"^ ?\* ?", "", ln).rstrip() for ln in m.group(1).split("\n")]
        text = "\n".join(lines).strip("\n")
        node = nodes.literal_block(text, text)
        node["language"] = "text"
        return [node]


def setup(app):
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    app.add_config_value("whirl_root", root, "env")
    app.add_config_value("whirl_program",
                         os.environ.get("WHIRL_PROGRAM", os.path.join(root, "build", "whirl")),
                         "env")
    app.add_directive("whirl-help", WhirlHelp)
    app.add_directive("whirl-opening", WhirlOpening)
    return {"version": "1", "parallel_read_safe": True}
