#!/usr/bin/python3
"""Runs the shell examples of Markdown documents as written and checks what they print.

  run_examples.py [DOC.md ...] [--junit DIR] [--log-dir DIR] [--list]

Each document (default: README.md, then docs/tutorial_*.md) runs in a shell of its own, from the
repository's top folder, block after block: see scripts/doc_examples/ for how blocks are marked
(`<!-- ci: not run: REASON -->`, `<!-- ci: save as FILE -->`), how expected outputs are written
(`#   -> key: value`) and checked, and how world lines (roslaunch, scripts/demo.sh) and background
jobs are started and stopped. Needs a built workspace ($IMPULSE2D_WS, as scripts/build.sh makes).
--junit writes one JUnit file per document, one test case per command. --list prints what would
run, without running it. Exit status: 0 when every command did what its document says, 1 when one
did not, 2 for a document that cannot be read as examples.
"""
import argparse
import glob
import os
import sys
import shutil
import signal
import tempfile
import time
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_examples import checks  # noqa: E402
from doc_examples.markdown import ExampleError, read_blocks  # noqa: E402
from doc_examples.session import Session, is_world_line  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMMAND_TIMEOUT = 180  # s; scripts/build.sh in a tutorial re-checks the whole build
WORLD_TIMEOUT = 300  # s; scripts/demo.sh installs what is missing and builds before it launches


class Case:
    def __init__(self, where, text, failure=None, seconds=0.0, output=""):
        self.where, self.text, self.failure = where, text, failure
        self.seconds, self.output = seconds, output

    def name(self):
        text = " ".join(self.text.split())
        return "%s %s" % (self.where, text if len(text) <= 90 else text[:87] + "...")


def run_document(path, log_dir, list_only, timeout):
    """The test cases of one document (its commands), printing each as it finishes."""
    shown = os.path.relpath(path, REPO)
    try:
        blocks = read_blocks(path, shown)
    except ExampleError as e:
        print("FAIL %s" % e, flush=True)
        return [Case("%s:%d" % (e.path, e.line), "(the document)", str(e))]
    if list_only:
        _list(blocks)
        return []
    os.makedirs(log_dir, exist_ok=True)
    session = Session(REPO, log_dir, timeout, WORLD_TIMEOUT)
    cases = []
    try:
        for block in blocks:
            where = "%s:%d" % (shown, block.line)
            if block.not_run:
                print("skip %s block (not run: %s)" % (where, block.not_run), flush=True)
            elif block.save_as:
                failure = session.save(block.save_as, block.text)
                if failure:
                    cases.append(_report(Case(where, "save as " + block.save_as, failure)))
            for command in block.commands:
                cases.append(_report(_run_command(session, command)))
                cases += _world_failures(session)
    finally:
        removed = session.close()
        cases += _world_failures(session)
        if removed:
            print("     %s: removed what it created: %s" % (shown, ", ".join(removed)), flush=True)
    return cases


def _run_command(session, command):
    if is_world_line(command.text):
        result = session.start_world(command.text, command.where())
        return Case(command.where(), command.text, result.failure, result.seconds)
    result = session.run(command.text)
    output = result.stdout + ("\n[stderr]\n" + result.stderr if result.stderr.strip() else "")
    if result.failure:
        return Case(command.where(), command.text, result.failure, result.seconds, output)
    found = checks.problems(command.text, result.status, result.stdout, result.stderr,
                            command.expected)
    return Case(command.where(), command.text, "; ".join(found) or None, result.seconds, output)


def _world_failures(session):
    """A failed case for each world line that showed trouble by the time it was stopped."""
    found = [_report(Case(where, "(until stopped) " + text, why))
             for where, text, why in session.world_failures]
    session.world_failures = []
    return found


def _report(case):
    print("%s %5.1f s  %s" % ("ok  " if case.failure is None else "FAIL", case.seconds, case.name()),
          flush=True)
    if case.failure:
        print("       " + case.failure.replace("\n", "\n       "))
        if case.output.strip():
            lines = case.output.rstrip().splitlines()
            print("       output%s:" % (" (last 20 lines)" if len(lines) > 20 else ""))
            print("\n".join("         " + line for line in lines[-20:]), flush=True)
    return case


def _list(blocks):
    for block in blocks:
        where = "%s:%d" % (block.path, block.line)
        if block.not_run:
            print("%s  not run: %s" % (where, block.not_run))
        elif block.save_as:
            print("%s  saved as %s" % (where, block.save_as))
        for command in block.commands:
            kind = "world" if is_world_line(command.text) else "run"
            print("%s  %-5s %s" % (command.where(), kind, " ".join(command.text.split())[:100]))
            for line, text in command.expected:
                print("%s        -> %s" % (" " * len(command.where()), text))


def write_junit(path, suite, cases):
    root = ET.Element("testsuite", name=suite, tests=str(len(cases)),
                      failures=str(sum(1 for c in cases if c.failure)),
                      time="%.1f" % sum(c.seconds for c in cases))
    for case in cases:
        element = ET.SubElement(root, "testcase", classname=suite, name=case.name(),
                                time="%.1f" % case.seconds)
        if case.failure:
            ET.SubElement(element, "failure", message=case.failure.split("\n")[0]).text = case.failure
            ET.SubElement(element, "system-out").text = case.output
    ET.ElementTree(root).write(path, encoding="utf-8", xml_declaration=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1].strip())
    parser.add_argument("docs", nargs="*", help="Markdown files (default: README.md, docs/tutorial_*.md)")
    parser.add_argument("--junit", help="a folder for one JUnit XML file per document")
    parser.add_argument("--log-dir", help="keep every command's output here (default: a temporary folder)")
    parser.add_argument("--list", action="store_true", help="print what would run, and run nothing")
    parser.add_argument("--timeout", type=float, default=COMMAND_TIMEOUT,
                        help="seconds a command may take (default %(default)s)")
    args = parser.parse_args()
    # A timeout's SIGTERM unwinds like Ctrl-C, so that each session stops what it started.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    docs = args.docs or [os.path.join(REPO, "README.md")] + sorted(
        glob.glob(os.path.join(REPO, "docs", "tutorial_*.md")))
    log_root = args.log_dir or tempfile.mkdtemp(prefix="impulse2d_examples.")
    started = time.monotonic()
    all_cases = []
    for doc in docs:
        doc = os.path.abspath(doc)
        if not os.path.isfile(doc):
            parser.error("no such document: %s" % doc)
        name = os.path.splitext(os.path.basename(doc))[0]
        print("=== %s" % os.path.relpath(doc, REPO), flush=True)
        cases = run_document(doc, os.path.join(log_root, name), args.list, args.timeout)
        if args.junit and not args.list:
            os.makedirs(args.junit, exist_ok=True)
            write_junit(os.path.join(args.junit, "examples_%s.xml" % name), "examples." + name, cases)
        all_cases += cases
    if not args.log_dir:
        shutil.rmtree(log_root, ignore_errors=True)
    if args.list:
        return 0
    failed = sum(1 for c in all_cases if c.failure)
    print("examples: %d commands, %d failed, %.0f s" % (len(all_cases), failed, time.monotonic() - started))
    if any(c.text == "(the document)" for c in all_cases):
        return 2
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
