"""Whether a command printed what its document says.

Every command must exit with status 0 and print no `ERROR:` line. Then:

- Expected outputs (`#   -> key: value, key: value` under the command) are read as the inside of
  a YAML flow mapping and compared with the first YAML document the command printed (rosservice
  prints its answer as YAML, rostopic echo each message): each key given must be there with that
  value; keys left out are not checked. Values compare exactly (`success: False`, a list of
  names, a quoted message), except that a value ending in `...` only has to begin with what comes
  before it (`message: "ok..."`, `0.334...`) and a lone `...` matches anything.
- With no expected `success`, every `rosservice call` answer that has a `success` field must say
  True: a call the document shows without comment is one that works.
- `rosservice call .../get_body_state` must answer a pose (finite x, y, theta).
- `rostopic echo` must print a message (`-n N`: N of them).
- `rosrun tf2_tools echo.py` must print a transform (a finite translation and rotation).
"""
import math
import re

import yaml

NUMBER = r"(-?[0-9.]+(?:e[-+]?[0-9]+)?|-?nan|-?inf)"
TRANSLATION = re.compile(r"^- Translation: \[%s, %s, %s\]" % (NUMBER, NUMBER, NUMBER), re.M)
ROTATION = re.compile(r"^- Rotation: in Quaternion \[%s, %s, %s, %s\]" % ((NUMBER,) * 4), re.M)
SERVICE_CALL = re.compile(r"\brosservice\s+call\s+(?:--wait\s+)?(\S+)")
TOPIC_ECHO = re.compile(r"\brostopic\s+echo\b(.*)")
TF_ECHO = re.compile(r"\btf2_tools\s+echo\.py\b")


def problems(text, status, stdout, stderr, expected):
    """What is wrong with the output of the command text (empty: it did what it says)."""
    found = []
    if status != 0:
        return ["exit status %d" % status]
    errors = [line for line in (stdout + stderr).splitlines() if line.startswith("ERROR:")]
    if errors:
        found.append("printed " + errors[0])
    answers = _yaml_mappings(stdout)
    wanted = {}
    for line, mapping in expected:
        try:
            value = yaml.safe_load("{" + mapping + "}")
        except yaml.YAMLError as e:
            found.append("line %d: the expected output is not YAML (%s)" % (line, str(e).split("\n")[0]))
            continue
        wanted.update(value)
        if not answers:
            found.append("line %d: expected `%s`, but the output has no YAML mapping" % (line, mapping))
        else:
            found += match(value, answers[0], "")
    if SERVICE_CALL.search(text):
        found += _service_checks(text, answers, wanted)
    echo = TOPIC_ECHO.search(text)
    if echo:
        count = re.search(r"-n\s*([0-9]+)", echo.group(1))
        wanted_messages = int(count.group(1)) if count else 1
        messages = sum(1 for line in stdout.splitlines() if line == "---")
        if messages < wanted_messages or not answers:
            found.append("printed %d messages, expected %d" % (messages, wanted_messages))
    if TF_ECHO.search(text):
        found += _transform_checks(stdout)
    return found


def match(expected, actual, where):
    """The differences between an expected value (from YAML) and an actual one."""
    if isinstance(expected, dict):
        if not isinstance(actual, dict):
            return ["%s: expected a mapping, got %r" % (where or "answer", actual)]
        out = []
        for key, value in expected.items():
            name = "%s.%s" % (where, key) if where else str(key)
            if key not in actual:
                out.append("%s: missing (the answer has %s)" % (name, ", ".join(map(str, actual))))
            else:
                out += match(value, actual[key], name)
        return out
    if isinstance(expected, list):
        if not isinstance(actual, list) or len(actual) != len(expected):
            return ["%s: expected %s, got %s" % (where, _show(expected), _show(actual))]
        out = []
        for i, (e, a) in enumerate(zip(expected, actual)):
            out += match(e, a, "%s[%d]" % (where, i))
        return out
    if isinstance(expected, str) and expected.endswith("..."):
        if _text(actual).startswith(expected[:-3]):
            return []
        return ["%s: expected %s (the beginning), got %s" % (where, _show(expected), _show(actual))]
    same_kind = isinstance(expected, bool) == isinstance(actual, bool)  # True is not 1
    if same_kind and expected == actual:
        return []
    return ["%s: expected %s, got %s" % (where, _show(expected), _show(actual))]


def _service_checks(text, answers, wanted):
    found = []
    if "success" not in wanted:
        for answer in answers:
            if answer.get("success") is False:
                found.append("answered success: False, message: %s" % _show(answer.get("message")))
    if any(name.endswith("get_body_state") for name in SERVICE_CALL.findall(text)):
        poses = [a["pose"] for a in answers if isinstance(a.get("pose"), dict)]
        if not poses or not all(_finite(poses[0].get(k)) for k in ("x", "y", "theta")):
            found.append("answered no pose with finite x, y, theta")
    return found


def _transform_checks(stdout):
    translation, rotation = TRANSLATION.search(stdout), ROTATION.search(stdout)
    if not translation or not rotation:
        return ["printed no transform (no `- Translation: [...]` and `- Rotation: ...` lines)"]
    numbers = [float(x) for x in translation.groups() + rotation.groups()]
    if not all(math.isfinite(x) for x in numbers):
        return ["printed a transform that is not finite: %s" % translation.group(0)]
    return []


def _yaml_mappings(stdout):
    """The YAML mappings printed, in order ([] when the output is not YAML)."""
    try:
        return [d for d in yaml.safe_load_all(stdout) if isinstance(d, dict)]
    except yaml.YAMLError:
        return []


def _finite(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _text(value):
    return value if isinstance(value, str) else repr(value)


def _show(value):
    return '"%s"' % value if isinstance(value, str) else repr(value)
