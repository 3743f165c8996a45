"""One document's commands, run in order in one shell, as a user types them into a terminal.

- The shell starts as a new terminal would: Debian's python3 first on PATH, no catkin workspace
  sourced, no DISPLAY, and ROS_MASTER_URI on a free port of its own (so it never reaches a master
  that something else runs on this machine); ROS_IP is 127.0.0.1 and ROS logs stay in the run's
  log folder. Variables, `source` and `cd` carry from one command to the next.
- A world line (`roslaunch ...`, or `scripts/demo.sh` without `--headless`) runs until stopped,
  as in a first terminal: it is started in the background on a master of its own (a new free
  port; roslaunch starts the master), and the next command waits until a world answers there
  (a `~get_body_state` service is advertised). A later world line first stops the earlier one.
  The shell's ROS_MASTER_URI then points at the newest world. A world line fails when its
  output shows a node that died or an `[ERROR]` line, up to when it is stopped (so RViz
  without a display, or a scene the node refuses, is not taken for a working example).
- A line ending in `&` runs in the background; it is stopped when a new world line starts and
  at the end of the document.
- Every command has a time limit; after one runs over, the rest of the document is not run.
- At the end everything started is stopped (SIGINT, as Ctrl-C would; SIGKILL after 20 s), also
  on failure, and the files the document created in its folder are removed.
"""
import os
import re
import select
import shlex
import shutil
import signal
import socket
import subprocess
import time

import rosgraph

DONE = "__impulse2d_example_done__"
STOP_GRACE = 20.0  # s from SIGINT to SIGKILL (roslaunch gives its nodes 15 s)
POLL = 0.25  # s between looks at a starting world
# What a catkin workspace's setup script sets: a document starts without any.
WORKSPACE_VARIABLES = ("ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH", "PYTHONPATH", "LD_LIBRARY_PATH",
                       "PKG_CONFIG_PATH", "ROSLISP_PACKAGE_DIRECTORIES", "ROS_ROOT", "ROS_ETC_DIR")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def is_world_line(text):
    """Whether the command starts a world that runs until stopped."""
    try:
        words = shlex.split(text, comments=True)
    except ValueError:
        return False
    while words and "=" in words[0] and not words[0].startswith("="):
        words.pop(0)  # VAR=value before the command
    if not words:
        return False
    if os.path.basename(words[0]) == "roslaunch":
        return True
    return words[0].endswith("scripts/demo.sh") and "--headless" not in words


class Result:
    def __init__(self, status, stdout="", stderr="", failure=None, seconds=0.0):
        self.status, self.stdout, self.stderr = status, stdout, stderr
        self.failure = failure  # set when the command could not be judged on its output
        self.seconds = seconds


class Session:
    def __init__(self, cwd, log_dir, command_timeout, world_timeout):
        self.cwd, self.log_dir = cwd, log_dir
        self.command_timeout, self.world_timeout = command_timeout, world_timeout
        self.count = 0
        self.world_pid = None
        self.world_log = None
        self.world_failures = []  # (where, text, why) of world lines found broken when stopped
        self.broken = None  # why the rest of the document cannot run
        self._buffer = b""  # what the shell printed and _wait_done has not read yet
        self.entries_before = set(os.listdir(cwd))
        self.master_uri = "http://127.0.0.1:%d" % free_port()
        env = {k: v for k, v in os.environ.items()
               if k not in WORKSPACE_VARIABLES and not k.startswith("ROS_") and k != "DISPLAY"}
        env.update(PATH="/usr/bin:" + env.get("PATH", "/bin"), ROS_MASTER_URI=self.master_uri,
                   ROS_IP="127.0.0.1", ROS_HOME=os.path.join(log_dir, "ros"),
                   ROS_LOG_DIR=os.path.join(log_dir, "ros", "log"))
        # set -m: each background job gets a process group of its own, and SIGINT reaches it as
        # Ctrl-C would (without job control, background jobs ignore SIGINT).
        self.shell = subprocess.Popen(["bash", "--noprofile", "--norc"], cwd=cwd, env=env,
                                      stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT, start_new_session=True)
        self._send("set -m\n")

    # --- commands ---------------------------------------------------------------------------
    def run(self, text):
        """Runs one command in the shell; its output goes to files of its own."""
        if self.broken:
            return Result(None, failure="not run: " + self.broken)
        self.count += 1
        out, err = (os.path.join(self.log_dir, "%03d.%s" % (self.count, s)) for s in ("out", "err"))
        started = time.monotonic()
        self._send("{ %s\n} >%s 2>%s </dev/null\nprintf '\\n%s %%d\\n' \"$?\"\n"
                   % (text, shlex.quote(out), shlex.quote(err), DONE))
        status = self._wait_done(self.command_timeout)
        seconds = time.monotonic() - started
        stdout, stderr = _read(out), _read(err)
        if status is None:
            self.broken = "`%s` ran over %d s" % (_short(text), self.command_timeout)
            return Result(None, stdout, stderr, "did not finish within %d s; a command that runs "
                          "until stopped needs a bounded form (rostopic echo -n 1, rostopic pub -1, "
                          "echo.py --limit N), a `&`, or its block marked `ci: not run`"
                          % self.command_timeout, seconds)
        return Result(status, stdout, stderr, seconds=seconds)

    def start_world(self, text, where=""):
        """Starts a world line in the background and waits until a world answers on its master;
        where (its place in the document) names it if it shows trouble later."""
        if self.broken:
            return Result(None, failure="not run: " + self.broken)
        self.stop_background()
        self.count += 1
        log = os.path.join(self.log_dir, "%03d.world.log" % self.count)
        self.world_log, self.world_text, self.world_where = log, text, where
        self.master_uri = "http://127.0.0.1:%d" % free_port()
        started = time.monotonic()
        self._send("export ROS_MASTER_URI=%s\n{ %s\n} >%s 2>&1 </dev/null &\nprintf '\\n%s %%d\\n' \"$!\"\n"
                   % (self.master_uri, text, shlex.quote(log), DONE))
        self.world_pid = self._wait_done(10)
        failure = None
        if self.world_pid is None:
            self.broken = "the shell did not start `%s`" % _short(text)
            failure = self.broken
        else:
            failure = self._wait_world(log)
        if failure:
            self.world_log = None  # reported once is enough
        return Result(0 if failure is None else 1, _read(log), "", failure, time.monotonic() - started)

    def _wait_world(self, log):
        master = rosgraph.Master("/impulse2d_doc_examples", master_uri=self.master_uri)
        deadline = time.monotonic() + self.world_timeout
        while time.monotonic() < deadline:
            if not _alive(self.world_pid):
                return "ended before a world came up on %s:\n%s" % (self.master_uri, _tail(_read(log)))
            try:
                services = master.getSystemState()[2]
                if any(name.endswith("/get_body_state") for name, _ in services):
                    return _launch_trouble(_read(log))
            except (OSError, rosgraph.MasterException):
                pass  # no master yet
            time.sleep(POLL)
        return "no world (a ~get_body_state service) came up on %s within %d s:\n%s" % (
            self.master_uri, self.world_timeout, _tail(_read(log)))

    def save(self, name, text):
        """Writes a block marked `ci: save as NAME` into the document's folder."""
        path = os.path.join(self.cwd, name)
        if name in self.entries_before:
            return "%s is there already; the document would overwrite it" % path
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        return None

    # --- stopping -------------------------------------------------------------------------
    def stop_background(self):
        """Stops the world line and the background jobs, as Ctrl-C in their terminals would."""
        if self.world_log:
            trouble = _launch_trouble(_read(self.world_log))
            if trouble:
                self.world_failures.append((self.world_where, self.world_text, "while it ran: " + trouble))
        jobs = [pid for pid in _children(self.shell.pid)]
        if self.world_pid and self.world_pid not in jobs and _alive(self.world_pid):
            jobs.append(self.world_pid)
        _stop(jobs)
        self.world_pid = self.world_log = None

    def close(self):
        """Stops everything the document started and removes the files it created."""
        try:
            self.stop_background()
        finally:
            try:
                self.shell.stdin.close()
                self.shell.wait(timeout=5)
            except (OSError, subprocess.TimeoutExpired):
                pass
            _stop([self.shell.pid])
            self.shell.wait()
        removed = []
        for entry in sorted(set(os.listdir(self.cwd)) - self.entries_before):
            path = os.path.join(self.cwd, entry)
            if os.path.isdir(path) and not os.path.islink(path):
                shutil.rmtree(path, ignore_errors=True)
            else:
                os.remove(path)
            removed.append(entry)
        return removed

    # --- the shell ------------------------------------------------------------------------
    def _send(self, text):
        self.shell.stdin.write(text.encode())
        self.shell.stdin.flush()

    def _wait_done(self, timeout):
        """The number after the shell's next DONE line, or None after timeout seconds."""
        deadline = time.monotonic() + timeout
        while True:
            while b"\n" in self._buffer:
                line, self._buffer = self._buffer.split(b"\n", 1)
                if line.startswith(DONE.encode()):
                    return int(line.split()[1])
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self.shell.stdout], [], [], left)[0]:
                return None
            chunk = os.read(self.shell.stdout.fileno(), 65536)
            if not chunk:
                return None  # the shell is gone
            self._buffer += chunk


def _stop(pids):
    """SIGINT to each process's group, then SIGKILL to what is left of them and below them."""
    pids = [p for p in pids if _alive(p)]
    if not pids:
        return
    doomed = set(pids)
    for pid in pids:
        doomed |= _descendants(pid)  # roslaunch's nodes run in sessions of their own
    for pid in pids:
        try:
            os.killpg(pid, signal.SIGINT)
        except OSError:
            try:
                os.kill(pid, signal.SIGINT)
            except OSError:
                pass
    deadline = time.monotonic() + STOP_GRACE
    while time.monotonic() < deadline and any(_alive(p) for p in doomed):
        for pid in list(doomed):
            doomed |= _descendants(pid) if _alive(pid) else set()
        time.sleep(POLL)
    for pid in doomed:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


def _launch_trouble(log):
    """What went wrong in a launch's output so far: a node that died, or an [ERROR] line."""
    for line in log.splitlines():
        if "process has died" in line or re.search(r"\[ERROR\]", line):
            return re.sub(r"\x1b\[[0-9;]*m", "", line).strip()
    return None


def _alive(pid):
    """Running (a zombie, dead but not yet reaped, counts as gone)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


def _children(pid):
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open("/proc/%s/stat" % entry) as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == pid:
                        found.append(int(entry))
            except (OSError, IndexError, ValueError):
                pass
    return found


def _descendants(pid):
    found = set()
    for child in _children(pid):
        found.add(child)
        found |= _descendants(child)
    return found


def _read(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.read()
    except OSError:
        return ""


def _tail(text, lines=15):
    return "\n".join("    " + line for line in text.splitlines()[-lines:])


def _short(text, width=70):
    text = " ".join(text.split())
    return text if len(text) <= width else text[:width - 3] + "..."
