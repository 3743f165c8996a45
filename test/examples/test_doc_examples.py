#!/usr/bin/python3
"""Unit tests of scripts/doc_examples: how blocks, markers and expected outputs are read, and how
outputs are judged. No ROS master needed. `--junit FILE` writes one JUnit test case per test."""
import os
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from doc_examples import checks  # noqa: E402
from doc_examples.markdown import ExampleError, read_blocks  # noqa: E402
from doc_examples.session import _launch_trouble, is_world_line  # noqa: E402


def blocks_of(text):
    with tempfile.NamedTemporaryFile("w", suffix=".md", delete=False) as f:
        f.write(text)
    try:
        return read_blocks(f.name, "doc.md")
    finally:
        os.remove(f.name)


ANSWER = 'success: False\nmessage: "body.shapes[0].width: must be finite and > 0"\n'
POSE = "success: True\nmessage: \"ok\"\npose: \n  x: 1.5\n  y: -2.0\n  theta: 0.25\n"
TRANSFORM = ("At time 12.3, (current time 12.4)\n- Translation: [-11.500, 0.000, 8.960]\n"
             "- Rotation: in Quaternion [0.000, 0.123, 0.000, 0.992]\n")


class Markdown(unittest.TestCase):
    def test_commands_continuations_and_expected_outputs(self):
        blocks = blocks_of("text\n\n```sh\nfirst \\\n  --flag\n#   -> success: False\n"
                           "# a note\n#   -> message: \"x\"\n\nsecond   # comment\n```\n")
        commands = blocks[0].commands
        self.assertEqual([c.text for c in commands], ["first \\\n  --flag", "second   # comment"])
        self.assertEqual([c.line for c in commands], [4, 10])
        self.assertEqual(commands[0].expected, [(6, "success: False"), (8, 'message: "x"')])
        self.assertEqual(commands[1].expected, [])

    def test_markers_before_a_block(self):
        blocks = blocks_of("<!-- ci: not run: needs a display -->\n\n```sh\nrviz\n```\n"
                           "<!-- ci: save as arm.urdf -->\n```xml\n<robot/>\n```\n```yaml\na: 1\n```\n")
        self.assertEqual(blocks[0].not_run, "needs a display")
        self.assertEqual(blocks[0].commands, [])
        self.assertEqual((blocks[1].save_as, blocks[1].text), ("arm.urdf", "<robot/>\n"))
        self.assertEqual((blocks[2].not_run, blocks[2].save_as, blocks[2].commands), (None, None, []))

    def test_bad_markers_are_refused_with_their_line(self):
        for text, line, words in [
                ("<!-- ci: skip this -->\n```sh\na\n```\n", 1, "unknown marker"),
                ("<!-- ci: not run: -->\n```sh\na\n```\n", 1, "needs the reason"),
                ("<!-- ci: save as ../x -->\n```sh\na\n```\n", 1, "plain file name"),
                ("<!-- ci: not run: why -->\nprose\n```sh\na\n```\n", 1, "last line before a block"),
                ("```sh\n#   -> success: True\n```\n", 2, "needs a command"),
                ("```sh\na\n\n#   -> success: True\n```\n", 4, "needs a command"),
                ("```sh\ncat <<EOF\nx\nEOF\n```\n", 2, "here-documents"),
                ("```sh\na \\\n```\n", 2, "continued line"),
                ("```sh\na\n", 1, "never closed")]:
            with self.assertRaises(ExampleError, msg=text) as caught:
                blocks_of(text)
            self.assertEqual(caught.exception.line, line, text)
            self.assertIn(words, str(caught.exception), text)

    def test_here_strings_are_commands(self):
        self.assertEqual(len(blocks_of("```sh\ngrep x <<<'xy'\n```\n")[0].commands), 1)


class Checks(unittest.TestCase):
    def problems(self, text, stdout, expected=(), status=0, stderr=""):
        return checks.problems(text, status, stdout, stderr, [(9, e) for e in expected])

    def test_exit_status_and_error_lines_fail(self):
        self.assertEqual(self.problems("true", "", status=1), ["exit status 1"])
        self.assertTrue(self.problems("x", "", stderr="ERROR: Unable to load type [std_srvs/Empty]"))

    def test_expected_values_compare_exactly_or_by_beginning(self):
        call = "rosservice call /impulse2d/spawn_body '...'"
        exact = 'success: False, message: "body.shapes[0].width: must be finite and > 0"'
        self.assertEqual(self.problems(call, ANSWER, [exact]), [])
        self.assertEqual(self.problems(call, ANSWER, ['success: False, message: "body.shapes[0]..."']), [])
        self.assertEqual(len(self.problems(call, ANSWER, ['success: False, message: "body.shapes[0].width"'])), 1)
        self.assertEqual(len(self.problems(call, ANSWER, ["success: True"])), 1)
        self.assertEqual(len(self.problems(call, ANSWER, ["success: 0"])), 1)  # False is not 0
        self.assertEqual(len(self.problems(call, ANSWER, ["success: False, bodies: [a]"])), 1)
        self.assertEqual(len(self.problems(call, "not: [yaml", ["success: False"])), 1)
        self.assertIn("not YAML", self.problems(call, ANSWER, ["success: [False"])[0])

    def test_lists_and_numbers(self):
        echo = "rostopic echo -n 1 /joint_states"
        message = "name: [arm/shoulder, arm/elbow]\nposition: [0.3341, -0.3712]\n---\n"
        self.assertEqual(self.problems(echo, message, ["name: [arm/shoulder, arm/elbow]"]), [])
        self.assertEqual(self.problems(echo, message, ["position: [0.334..., -0.371...]"]), [])
        self.assertEqual(len(self.problems(echo, message, ["position: [0.335..., ...]"])), 1)
        self.assertEqual(len(self.problems(echo, message, ["name: [arm/shoulder]"])), 1)

    def test_a_call_shown_without_comment_must_succeed(self):
        self.assertEqual(len(self.problems("rosservice call /w/spawn_body '{}'", ANSWER)), 1)
        self.assertEqual(self.problems("rosservice call /w/pause", "\n"), [])

    def test_get_body_state_answers_a_pose(self):
        call = "rosservice call /impulse2d/get_body_state crate"
        self.assertEqual(self.problems(call, POSE), [])
        self.assertEqual(len(self.problems(call, 'success: True\nmessage: "ok"\n')), 1)
        self.assertEqual(len(self.problems(call, POSE.replace("0.25", "nan"))), 1)

    def test_topic_echo_prints_its_messages(self):
        self.assertEqual(self.problems("rostopic echo -n 1 /c", "a: 1\n---\n"), [])
        self.assertEqual(len(self.problems("rostopic echo -n 2 /c", "a: 1\n---\n")), 1)
        self.assertEqual(len(self.problems("rostopic echo -n 1 /c", "")), 1)

    def test_tf_echo_prints_a_transform(self):
        echo = "rosrun tf2_tools echo.py world link --limit 3"
        self.assertEqual(self.problems(echo, TRANSFORM), [])
        self.assertEqual(len(self.problems(echo, "")), 1)
        self.assertEqual(len(self.problems(echo, TRANSFORM.replace("-11.500", "nan"))), 1)


class WorldLines(unittest.TestCase):
    def test_which_lines_start_a_world(self):
        for text in ["roslaunch impulse2d demo.launch rviz:=false", "X=1 roslaunch a b.launch",
                     "scripts/demo.sh rviz:=false   # runs until Ctrl-C", "./scripts/demo.sh"]:
            self.assertTrue(is_world_line(text), text)
        for text in ["scripts/demo.sh --headless", "rosrun nodelet nodelet manager &",
                     "echo roslaunch", "# roslaunch x y", "rosservice call /x 'unclosed"]:
            self.assertFalse(is_world_line(text), text)


    def test_a_launch_with_a_dead_node_or_an_error_is_in_trouble(self):
        self.assertIsNone(_launch_trouble("process[impulse2d-2]: started with pid [12]\n"
                                          "[ WARN] [1.0]: no ~scene parameter\n"))
        self.assertIn("rviz-3", _launch_trouble("\x1b[1m[rviz-3] process has died [pid 1]\x1b[0m\n"))
        self.assertIn("~scene", _launch_trouble("[ERROR] [1.0]: [/impulse2d] ~scene: bad\n"))


class JUnitResult(unittest.TextTestResult):
    """Remembers each test's outcome for the JUnit file."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.outcomes = []

    def addSuccess(self, test):
        super().addSuccess(test)
        self.outcomes.append((test.id(), None))

    def addFailure(self, test, err):
        super().addFailure(test, err)
        self.outcomes.append((test.id(), self._exc_info_to_string(err, test)))

    def addError(self, test, err):
        super().addError(test, err)
        self.outcomes.append((test.id(), self._exc_info_to_string(err, test)))


def run_with_junit(module, suite_name):
    """Runs the module's tests; with `--junit FILE` on the command line writes them as JUnit."""
    junit = sys.argv[sys.argv.index("--junit") + 1] if "--junit" in sys.argv else None
    suite = unittest.defaultTestLoader.loadTestsFromModule(module)
    result = unittest.TextTestRunner(resultclass=JUnitResult, verbosity=1).run(suite)
    if junit:
        root = ET.Element("testsuite", name=suite_name, tests=str(len(result.outcomes)),
                          failures=str(sum(1 for _, f in result.outcomes if f)))
        for name, failure in result.outcomes:
            case = ET.SubElement(root, "testcase", classname=suite_name, name=name)
            if failure:
                ET.SubElement(case, "failure", message=failure.splitlines()[-1]).text = failure
        ET.ElementTree(root).write(junit, encoding="utf-8", xml_declaration=True)
    return 0 if result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(run_with_junit(sys.modules[__name__], "doc_examples_unit"))
