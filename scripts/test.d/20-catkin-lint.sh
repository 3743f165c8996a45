#!/usr/bin/env bash
# catkin_lint -W2 on the package: every error, warning and notice fails it, except those that
# CMakeLists.txt ignores on purpose (with the reasons there) and package_path_name (a checkout's
# folder may have any name). --offline: no queries to the ROS package index. JUnit XML: one test
# case per finding, or one passing case. Bound: a few seconds.
set -uo pipefail
REPO="${REPO:-$(cd "$(dirname "$0")/../.." && pwd)}"
export PATH="/usr/bin:$PATH"
results="${STAGE_RESULTS:-$(mktemp -d)}"
mkdir -p "$results"
command -v catkin_lint >/dev/null || { echo "catkin_lint is missing: apt-get install catkin-lint" >&2; exit 1; }

xml="$(timeout 120 catkin_lint -W2 --offline --ignore package_path_name --xml "$REPO" 2>/dev/null)"
rc=$?
python3 - "$results/catkin_lint.xml" "$rc" "$xml" <<'PY'
import sys, xml.etree.ElementTree as ET
out, rc, text = sys.argv[1], int(sys.argv[2]), sys.argv[3]
suite = ET.Element("testsuite", name="catkin_lint")
findings = []
try:
    for problem in ET.fromstring(text):
        location = problem.find("location")
        where = ":".join(e.text for e in (location.find("file"), location.find("line"))
                         if e is not None) if location is not None else ""
        findings.append((problem.findtext("id"), "%s: %s: %s" % (
            where or "package", problem.tag, problem.findtext("text"))))
except ET.ParseError as error:
    findings.append(("output", "catkin_lint exited %d without readable XML: %s" % (rc, error)))
if rc not in (0, 1) and not findings:
    findings.append(("exit", "catkin_lint exited %d" % rc))
for i, (ident, message) in enumerate(findings):
    case = ET.SubElement(suite, "testcase", classname="catkin_lint", name="%s_%d" % (ident, i))
    ET.SubElement(case, "failure", message=message).text = message
    print("catkin_lint: " + message)
if not findings:
    ET.SubElement(suite, "testcase", classname="catkin_lint", name="clean")
    print("catkin_lint -W2: clean")
suite.set("tests", str(max(1, len(findings))))
suite.set("failures", str(len(findings)))
ET.ElementTree(suite).write(out, encoding="utf-8", xml_declaration=True)
sys.exit(1 if findings else 0)
PY
