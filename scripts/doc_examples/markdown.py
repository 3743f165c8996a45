"""The fenced blocks of a Markdown file, and the commands and expected outputs of its shell blocks.

A block is marked for CI by an HTML comment on the last non-blank line before its fence (invisible
in the rendered page, visible in the source):

    <!-- ci: not run: RViz needs a display -->     the block is not run; the reason is required
    <!-- ci: save as my_arm.urdf -->               the block's text is written to that file (in
                                                   the folder the commands run in) when reached

In a shell block (```sh, ```bash or ```shell) each line is one command; a line ending in a
backslash continues on the next. A comment line `#   -> key: value, key: value` after a command
(other comment lines may come between, a blank line or the next command ends them) is an output
the command must give: see checks.py. Other comments are for the reader only.
"""
import re
from dataclasses import dataclass, field
from typing import List, Optional, Tuple

SHELL_LANGUAGES = ("sh", "bash", "shell")
FENCE = re.compile(r"^(```+|~~~+)\s*([\w+-]*)")
DIRECTIVE = re.compile(r"^<!--\s*ci:\s*(.*?)\s*-->\s*$")
EXPECTED = re.compile(r"^#\s*->\s?(.*)$")
HEREDOC = re.compile(r"(?<!<)<<-?\s*['\"]?[A-Za-z_]")  # not a here-string (<<<)


class ExampleError(Exception):
    """A document that cannot be run as written: the file and line say where."""

    def __init__(self, path, line, message):
        super().__init__("%s:%d: %s" % (path, line, message))
        self.path, self.line = path, line


@dataclass
class Command:
    path: str
    line: int  # of its first line in the file
    text: str  # continuation lines joined, as the shell reads them
    expected: List[Tuple[int, str]] = field(default_factory=list)  # (line, "key: value, ...")

    def where(self):
        return "%s:%d" % (self.path, self.line)


@dataclass
class Block:
    path: str
    line: int  # of the opening fence
    language: str
    text: str
    commands: List[Command]
    not_run: Optional[str] = None  # the reason given
    save_as: Optional[str] = None

    def is_shell(self):
        return self.language in SHELL_LANGUAGES


def read_blocks(path, display_path=None):
    """Every fenced block of the file at path, in order; raises ExampleError on a bad marker."""
    name = display_path or path
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    blocks = []
    last_text = None  # (line number, text) of the last non-blank line outside blocks
    i = 0
    while i < len(lines):
        opening = FENCE.match(lines[i])
        if not opening:
            if lines[i].strip():
                _refuse_stray_directive(name, last_text)
                last_text = (i + 1, lines[i].strip())
            i += 1
            continue
        fence, language = opening.group(1), opening.group(2).lower()
        end = i + 1
        while end < len(lines) and not lines[end].startswith(fence):
            end += 1
        if end == len(lines):
            raise ExampleError(name, i + 1, "the block opened here is never closed")
        body = lines[i + 1:end]
        block = Block(name, i + 1, language, "\n".join(body) + "\n", [])
        if last_text and DIRECTIVE.match(last_text[1]):
            _apply_directive(block, last_text[0], DIRECTIVE.match(last_text[1]).group(1))
        if block.is_shell() and block.not_run is None and block.save_as is None:
            block.commands = split_commands(name, i + 2, body)
        blocks.append(block)
        last_text = None
        i = end + 1
    _refuse_stray_directive(name, last_text)
    return blocks


def _apply_directive(block, line, directive):
    if directive.startswith("not run:"):
        reason = directive[len("not run:"):].strip()
        if not reason:
            raise ExampleError(block.path, line, "`ci: not run:` needs the reason after it")
        block.not_run = reason
    elif directive.startswith("save as "):
        target = directive[len("save as "):].strip()
        if not re.fullmatch(r"[A-Za-z0-9_.-]+", target) or target.startswith("."):
            raise ExampleError(block.path, line, "`ci: save as` takes a plain file name, not %r" % target)
        block.save_as = target
    else:
        raise ExampleError(block.path, line, "unknown marker `ci: %s` (known: `ci: not run: "
                           "REASON`, `ci: save as FILE`)" % directive)


def _refuse_stray_directive(path, last_text):
    """A marker must stand right before a block, or it would silently mark nothing."""
    if last_text and DIRECTIVE.match(last_text[1]):
        raise ExampleError(path, last_text[0], "a `ci:` marker must be the last line before a block")


def split_commands(path, first_line, body):
    """The commands of a shell block whose first line is line first_line of the file."""
    commands = []
    current = None  # the command that expected outputs attach to
    pending = []  # continuation lines of a command being joined
    pending_line = 0
    for offset, raw in enumerate(body):
        number = first_line + offset
        stripped = raw.strip()
        if pending:
            pending.append(raw)
        elif not stripped:
            current = None
            continue
        elif stripped.startswith("#"):
            expected = EXPECTED.match(stripped)
            if expected:
                if current is None:
                    raise ExampleError(path, number, "an expected output (`# ->`) needs a command "
                                       "right before it")
                current.expected.append((number, expected.group(1).strip()))
            continue
        else:
            pending, pending_line = [raw], number
        if raw.endswith("\\"):
            continue
        text = "\n".join(pending)
        pending = []
        if HEREDOC.search(text):
            raise ExampleError(path, pending_line, "here-documents cannot be run line by line: "
                               "write the file in a block marked `ci: save as FILE`")
        current = Command(path, pending_line, text)
        commands.append(current)
    if pending:
        raise ExampleError(path, pending_line, "the block ends inside a continued line")
    return commands
