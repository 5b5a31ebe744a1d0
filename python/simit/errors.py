"""The exceptions of the simit package.

Every error of the compiler and runtime is a simit.Error whose message is the
C++ API's: "springs.sim:12:5: error: ..." for the frontend,
"scene.json: sets.points.fields.x: ..." for scenes, "bunny.node:7: ..." for
meshes; "lowering failed" then the lowering's first "p.sim:3:7: error: ...".
The position it names, if any, is parsed into `file`, `line` and `column`.
"""

import re

# "file:line:col: ", "file:line: " or "file: " at the start of the message,
# where a file has a dot or slash in its name or is a <buffer name>.
_FILE = r"(?P<file><[^>\n]+>|[^:\s'\"()]*[./][^:\s'\"()]*)"
_AT_START = re.compile(_FILE + r"(?::(?P<line>\d+)(?::(?P<column>\d+))?)?: ")
# A later line "file:line:col: error: ": the first diagnostic of a lowering
# ("lowering failed" first).
_ON_A_LINE = re.compile(
    r"^" + _FILE + r":(?P<line>\d+):(?P<column>\d+): error: ", re.M)
# "(file:line:col)" inside a message: the statement check-numerics names.
_IN_PARENS = re.compile(r"\(" + _FILE + r":(?P<line>\d+):(?P<column>\d+)\)")


class Error(Exception):
    """An error of the Simit compiler or runtime.

    `file`, `line` and `column` locate it when the message does (None where
    it does not); `message` is the whole message.
    """

    def __init__(self, message):
        super().__init__(message)
        self.message = message
        match = (_AT_START.match(message) or _ON_A_LINE.search(message)
                 or _IN_PARENS.search(message))
        self.file = match.group("file") if match else None
        line = match.group("line") if match else None
        column = match.group("column") if match else None
        self.line = int(line) if line else None
        self.column = int(column) if column else None


class NumericsError(Error):
    """A NaN or infinity found by check_numerics=True, naming the assembly
    or solve that produced it (file, line, column) or the field it is in."""
