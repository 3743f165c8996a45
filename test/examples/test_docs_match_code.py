#!/usr/bin/python3
"""docs/ros_api.md against the code it documents: every message and service definition verbatim,
every launch argument, every service the node advertises. `--junit FILE` writes one JUnit test
case per test."""
import glob
import os
import re
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_doc_examples import run_with_junit  # noqa: E402

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def read(path):
    with open(os.path.join(REPO, path), encoding="utf-8") as f:
        return f.read()


class RosApi(unittest.TestCase):
    doc = read("docs/ros_api.md")

    def test_every_message_and_service_definition_is_shown_as_it_is(self):
        shown = dict(re.findall(r"^`((?:msg|srv)/\w+\.(?:msg|srv))`\n```\n(.*?)```", self.doc,
                                re.S | re.M))
        files = sorted(glob.glob(os.path.join(REPO, "msg", "*.msg")) +
                       glob.glob(os.path.join(REPO, "srv", "*.srv")))
        self.assertTrue(files)
        for path in files:
            name = os.path.relpath(path, REPO)
            self.assertIn(name, shown, "docs/ros_api.md does not show " + name)
            self.assertEqual(shown[name].strip(), read(name).strip(),
                             "docs/ros_api.md shows an old " + name)

    def test_every_launch_argument_is_in_the_launch_table(self):
        for path in sorted(glob.glob(os.path.join(REPO, "launch", "*.launch"))):
            name = os.path.basename(path)
            row = re.search(r"^\| `%s` \|([^\n]*)$" % re.escape(name), self.doc, re.M)
            self.assertIsNotNone(row, "docs/ros_api.md's launch table has no row for " + name)
            # The launch file's own arguments; <arg name=... value=...> passes one to an include.
            text = read(os.path.relpath(path, REPO))
            for argument in re.findall(r'<arg\s+name="(\w+)"(?![^>]*\svalue=)', text):
                self.assertIn("`%s`" % argument, row.group(1), "%s's argument %s" % (name, argument))

    def test_every_advertised_service_is_documented(self):
        sources = "".join(read(os.path.relpath(p, REPO))
                          for p in glob.glob(os.path.join(REPO, "src", "ros", "*.cpp")))
        services = set(re.findall(r'advertiseService\(\s*"(\w+)"', sources))
        self.assertIn("spawn_body", services)
        for service in sorted(services):
            self.assertIn("`~%s`" % service, self.doc, "docs/ros_api.md: ~" + service)


if __name__ == "__main__":
    sys.exit(run_with_junit(sys.modules[__name__], "docs_match_code"))
