#!/usr/bin/env python3
"""The ROS soak: client processes call every service of a running world at random.

    ros_soak.py [--seconds S] [--seed N] [--clients K] [--mode node|nodelet|both] [--junit FILE]

For each mode, starts soak_world.launch (the walled arena of issue 26 stepping at ~rate 0, as a
node or as a nodelet) on a master of its own, subscribes /tf, ~markers and ~contacts, and runs K
clients for S seconds (default 30). Each client spawns boxes, circles and polygons (some bullet,
one in five kinematic), deletes them, joins them with joints of all four types anchored anywhere,
deletes joints, teleports, pushes, sets motors, reads states, casts rays, queries points, pauses,
steps and unpauses, spawns, moves and deletes models (two jointed bodies with a laser and a
bumper, whose topics come and go), spawns URDF models (an arm on a hinge, whose bodies it then
treats as its own), and sends bad requests. A controller calls ~reset at a third of the run and
~load_scene at two thirds. Checked, each a JUnit case per mode:
  - every call answered within 1 s;
  - every bad request refused, every valid one accepted (or refused for a stated reason the
    world may have, such as a body gone after ~reset);
  - no body removed (~removed_bodies), and every body a client still holds present at the end
    and inside the arena;
  - ~reset and ~load_scene answered and effective;
  - the process's RSS bounded (at most 64 MiB above its value after warm-up);
  - the world alive at the end.
Prints the seed and the totals; a failure prints the seed and the last calls of the client.
"""
import argparse
import math
import multiprocessing as mp
import os
import random
import signal
import subprocess
import sys
import time
import traceback
from xml.sax.saxutils import escape

SLOW_CALL = 1.0  # s
RSS_GROWTH_LIMIT = 64 * 1024  # KiB
HALF_WIDTH, HEIGHT = 10.0, 20.0
# As the core soak counts it (soak_run.cpp): a body has left once past the middle of a 2 m wall
# (one resting on the ground or jammed between two walls sinks into them a little).
ARENA_SLACK = 1.0
KINEMATIC_REACH = 2.0  # m: kinematic bodies stay over 2 m (more than any body here) off the walls
# What ~spawn_model places: two bodies on a revolute joint with a laser and a bumper (their topics
# open and close with the model, under its namespace).
MODEL_YAML = """
bodies:
  - {name: base, shapes: [{type: box, size: [0.6, 0.3]}]}
  - {name: wheel, position: [0.3, -0.2], shapes: [{type: circle, radius: 0.12}]}
joints:
  - {name: axle, type: revolute, body_a: base, body_b: wheel, anchor: [0.3, -0.2]}
devices:
  - {type: laser, name: laser, body: base, angle_increment: 0.05, update_rate: 5}
  - {type: bumper, name: bumper, body: base}
"""

# What ~spawn_urdf places (the arena is the xz plane, so the hinge turns about 3D y): a base and
# an arm on a continuous joint (bodies "<model>/base" and
# "<model>/arm", which the client then treats as its own bodies: joined, pushed, deleted).
URDF_XML = """<robot name="arm">
  <link name="base"><inertial><mass value="2"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0"
    izz="0.05"/></inertial><collision><geometry><box size="0.5 0.3 0.2"/></geometry></collision>
  </link>
  <joint name="elbow" type="continuous"><parent link="base"/><child link="arm"/>
    <origin xyz="0.25 0 0"/><axis xyz="0 1 0"/></joint>
  <link name="arm"><inertial><origin xyz="0.3 0 0"/><mass value="0.5"/><inertia ixx="0" ixy="0"
    ixz="0" iyy="0" iyz="0" izz="0.01"/></inertial><collision><origin xyz="0.3 0 0"/><geometry>
    <box size="0.6 0.08 0.08"/></geometry></collision></link>
</robot>"""


def inside(pose, margin):
    """Whether a body's origin lies inside the arena, at least `margin` m off its walls (< 0:
    into them)."""
    return abs(pose.x) < HALF_WIDTH - margin and margin < pose.y < HEIGHT - margin


def rss_kib(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def find_pid(pattern):
    out = subprocess.run(["pgrep", "-f", pattern], capture_output=True, text=True).stdout.split()
    return int(out[0]) if out else None


class Client:
    """One client process: random calls against the world `ns` until `deadline`."""

    def __init__(self, index, seed, ns, deadline, generation):
        import rospy  # noqa: F401 (imported in the child)
        from impulse2d import msg, srv
        from std_srvs.srv import Empty
        self.rospy, self.msg, self.srv, self.Empty = rospy, msg, srv, Empty
        self.index, self.ns, self.deadline = index, ns, deadline
        self.generation, self.seen_generation = generation, generation.value
        self.random = random.Random(seed * 1000 + index)
        self.bodies, self.joints, self.next_name = [], [], 0
        self.kinematic = set()  # the names of our kinematic bodies
        self.models = {}  # model name -> its bodies' names
        self.last = []  # the last calls, for a failure report
        self.counts = {"calls": 0, "slow": 0, "bad": 0, "bad_accepted": 0, "refused": 0,
                       "unexpected": 0, "errors": 0, "bodies_made": 0, "joints_made": 0,
                       "models_made": 0, "urdf_made": 0, "slowest_ms": 0}
        self.failures = []
        self.proxies = {}

    def proxy(self, name, kind):
        # Persistent, as the C++ test clients: Debian's roscpp sometimes drops a one-shot service
        # connection on the server's hang-up before the response is read (ros/ros_comm#1976).
        if name not in self.proxies:
            self.proxies[name] = self.rospy.ServiceProxy(self.ns + "/" + name, kind, persistent=True)
        return self.proxies[name]

    def call(self, service, kind, request, expect=None, **fields):
        """Calls a service; expect True/False checks success; returns the response or None."""
        self.counts["calls"] += 1
        name = service
        self.last.append("%s %s" % (name, {k: str(v)[:80] for k, v in fields.items()}))
        self.last = self.last[-12:]
        start = time.monotonic()
        try:
            response = self.proxy(name, kind)(request)
        except Exception as e:  # a dead node, a broken connection
            self.counts["errors"] += 1
            self.fail("%s raised %s" % (name, e))
            return None
        took = time.monotonic() - start
        self.counts["slowest_ms"] = max(self.counts["slowest_ms"], int(1000 * took))
        if took > SLOW_CALL:
            self.counts["slow"] += 1
            self.fail("%s took %.2f s" % (name, took))
        ok = getattr(response, "success", True)
        if expect is False:
            self.counts["bad"] += 1
            if ok:
                self.counts["bad_accepted"] += 1
                self.fail("bad request %s was accepted: %s" % (name, response.message))
        elif expect is True and not ok:
            self.counts["refused"] += 1
            if not self.explained(response.message):
                self.counts["unexpected"] += 1
                self.fail("valid %s refused: %s" % (name, response.message))
        return response

    def explained(self, message):
        # A body or joint of ours gone: ~reset removed it (the generation says so), or the world
        # holds two bodies no joint can join (neither dynamic).
        # The generation is odd while a ~reset is under way.
        if self.generation.value != self.seen_generation or self.generation.value % 2 == 1:
            return True
        return "at least one of the two bodies must be dynamic" in message

    def fail(self, text):
        if len(self.failures) < 20:
            self.failures.append("client %d: %s; last calls: %s" % (self.index, text,
                                                                    " | ".join(self.last)))

    def sync_generation(self):
        if self.generation.value != self.seen_generation:
            self.seen_generation = self.generation.value
            self.bodies, self.joints, self.models = [], [], {}
            self.kinematic = set()

    # --- requests ---
    def point(self, margin=0.0):
        return (self.random.uniform(-HALF_WIDTH + margin, HALF_WIDTH - margin),
                self.random.uniform(margin, HEIGHT - margin))

    def shape(self):
        m = self.msg
        s = m.Shape()
        kind = self.random.randrange(3)
        if kind == 0:
            s.type, s.width, s.height = m.Shape.BOX, self.random.uniform(0.1, 1.2), self.random.uniform(0.1, 1.2)
        elif kind == 1:
            s.type, s.radius = m.Shape.CIRCLE, self.random.uniform(0.05, 0.6)
        else:
            from geometry_msgs.msg import Point
            s.type = m.Shape.POLYGON
            n, r = self.random.randint(3, 8), self.random.uniform(0.1, 0.7)
            s.vertices = [Point(r * math.cos(2 * math.pi * (i + self.random.uniform(0, 0.4)) / n),
                                r * math.sin(2 * math.pi * (i + self.random.uniform(0, 0.4)) / n), 0)
                          for i in range(n)]
        if self.random.random() < 0.5:
            s.density = self.random.uniform(0.1, 5.0)
        if self.random.random() < 0.5:
            s.friction = self.random.uniform(0.0, 1.0)
        if self.random.random() < 0.3:
            s.restitution = self.random.uniform(0.0, 0.9)
        return s

    def new_name(self, kind):
        """A name of ours no other client uses: c<client>_<kind><serial>."""
        self.next_name += 1
        return "c%d_%s%d" % (self.index, kind, self.next_name - 1)

    def place(self, pose, margin):
        """A random pose anywhere inside the arena, `margin` m off its walls."""
        pose.x, pose.y = self.point(margin)
        pose.theta = self.random.uniform(-math.pi, math.pi)

    # A kinematic body starts well inside and moves at most KINEMATIC_REACH m by the run's end: it
    # may never press a dynamic body into the walls, nor carry one out, so any dynamic body outside
    # at the end is the solver's doing.
    def kinematic_point(self):
        return self.random.uniform(-5, 5), self.random.uniform(5, 15)

    def kinematic_twist(self, twist):
        speed = KINEMATIC_REACH / max(1.0, self.deadline - time.time()) / math.sqrt(2.0)
        twist.linear.x, twist.linear.y = self.random.uniform(-speed, speed), self.random.uniform(-speed, speed)
        twist.angular.z = self.random.uniform(-1, 1)

    def spawn(self):
        m = self.msg
        body = m.Body()
        body.name = self.new_name("b")
        kinematic = self.random.random() < 0.2
        body.type = m.Body.KINEMATIC if kinematic else m.Body.DYNAMIC
        x, y = self.point(1.0) if not kinematic else self.kinematic_point()
        body.pose.x, body.pose.y, body.pose.theta = x, y, self.random.uniform(-math.pi, math.pi)
        if kinematic:
            self.kinematic_twist(body.twist)
        else:
            body.twist.linear.x, body.twist.linear.y = self.random.uniform(-5, 5), self.random.uniform(-5, 5)
        body.shapes = [self.shape()]
        body.bullet = self.random.random() < 0.1
        response = self.call("spawn_body", self.srv.SpawnBody, self.srv.SpawnBodyRequest(body=body),
                             expect=True, name=body.name)
        if response is not None and response.success:
            self.bodies.append(body.name)
            if kinematic:
                self.kinematic.add(body.name)
            self.counts["bodies_made"] += 1

    def delete(self):
        if not self.bodies:
            return
        name = self.bodies.pop(self.random.randrange(len(self.bodies)))
        self.kinematic.discard(name)
        self.call("delete_body", self.srv.DeleteBody, self.srv.DeleteBodyRequest(name=name),
                  expect=True, name=name)
        self.joints = [j for j in self.joints if name not in j[1:3]]

    def join(self):
        if len(self.bodies) < 2:
            return
        m = self.msg
        a, b = self.random.sample(self.bodies, 2)
        joint = m.Joint()
        joint.name = self.new_name("j")
        joint.type = self.random.randrange(4)
        joint.body_a, joint.body_b = a, b
        joint.anchor.x, joint.anchor.y = self.point()
        angle = self.random.uniform(-math.pi, math.pi)
        joint.axis.x, joint.axis.y = math.cos(angle), math.sin(angle)
        if joint.type == m.Joint.DISTANCE:
            joint.length = self.random.uniform(0.2, 3.0)
        if joint.type in (m.Joint.REVOLUTE, m.Joint.PRISMATIC) and self.random.random() < 0.3:
            joint.enable_limit, joint.lower, joint.upper = True, self.random.uniform(-1, 0), self.random.uniform(0, 1)
        if joint.type in (m.Joint.REVOLUTE, m.Joint.PRISMATIC) and self.random.random() < 0.2:
            joint.enable_motor = True
            joint.motor_speed, joint.max_motor_torque = self.random.uniform(-5, 5), self.random.uniform(0, 100)
        joint.collide_connected = self.random.random() < 0.3
        response = self.call("create_joint", self.srv.CreateJoint,
                             self.srv.CreateJointRequest(joint=joint), expect=True,
                             name=joint.name, type=joint.type)
        if response is not None and response.success:
            self.joints.append((joint.name, a, b, joint.type == m.Joint.WELD))
            self.counts["joints_made"] += 1

    def unjoin(self):
        if not self.joints:
            return
        name = self.joints.pop(self.random.randrange(len(self.joints)))[0]
        self.call("delete_joint", self.srv.DeleteJoint, self.srv.DeleteJointRequest(name=name),
                  expect=True, name=name)

    def welded_to(self, name):
        """The bodies our welds join to `name`, directly or not (a teleport moves them along)."""
        group, todo = {name}, [name]
        while todo:
            at = todo.pop()
            for _, a, b, weld in self.joints:
                for one, other in ((a, b), (b, a)):
                    if weld and one == at and other not in group:
                        group.add(other)
                        todo.append(other)
        return group - {name}

    def teleport(self):
        if not self.bodies:
            return
        r = self.srv.SetBodyStateRequest(name=self.random.choice(self.bodies))
        self.place(r.pose, 1.5)
        speed, angle = self.random.uniform(0, 5), self.random.uniform(-math.pi, math.pi)
        r.twist.linear.x, r.twist.linear.y = speed * math.cos(angle), speed * math.sin(angle)
        r.twist.angular.z = self.random.uniform(-5, 5)
        if r.name in self.kinematic:
            r.pose.x, r.pose.y = self.kinematic_point()
            self.kinematic_twist(r.twist)
        # The bodies welded to it come along, rigidly: as the core soak's user, this one keeps
        # them inside the walls, putting the body back where it was when one would not be.
        partners = self.welded_to(r.name)
        get = self.proxy("get_body_state", self.srv.GetBodyState)
        before = get(self.srv.GetBodyStateRequest(name=r.name)) if partners else None
        response = self.call("set_body_state", self.srv.SetBodyState, r, name=r.name)
        if response is not None and not response.success and not self.explained(response.message):
            self.counts["unexpected"] += 1
            self.fail("valid set_body_state refused: %s" % response.message)
        if before is None or not before.success or response is None or not response.success:
            return
        for other in partners:
            state = get(self.srv.GetBodyStateRequest(name=other))
            if state.success and not inside(state.pose, 0.5):
                back = self.srv.SetBodyStateRequest(name=r.name, pose=before.pose, twist=before.twist)
                self.call("set_body_state", self.srv.SetBodyState, back, name=r.name)
                break

    def push(self):
        if not self.bodies:
            return
        r = self.srv.ApplyWrenchRequest(body=self.random.choice(self.bodies))
        f, angle = self.random.uniform(0, 200), self.random.uniform(-math.pi, math.pi)
        r.force.x, r.force.y = f * math.cos(angle), f * math.sin(angle)
        r.torque = self.random.uniform(-20, 20)
        r.point.x, r.point.y = self.point()
        r.duration = self.random.uniform(0, 0.5)
        # Refused for a kinematic body (forces move only dynamic ones): not checked.
        self.call("apply_wrench", self.srv.ApplyWrench, r, body=r.body)

    def read(self):
        kind = self.random.randrange(4)
        if kind == 0 and self.bodies:
            self.call("get_body_state", self.srv.GetBodyState,
                      self.srv.GetBodyStateRequest(name=self.random.choice(self.bodies)), expect=True)
        elif kind == 1:
            r = self.srv.RayCastRequest()
            r.start.x, r.start.y = self.point()
            r.end.x, r.end.y = self.point()
            self.call("ray_cast", self.srv.RayCast, r, expect=True)
        elif kind == 2:
            r = self.srv.QueryPointRequest()
            r.point.x, r.point.y = self.point()
            self.call("query_point", self.srv.QueryPoint, r, expect=True)
        elif self.bodies:
            self.call("get_body_properties", self.srv.GetBodyProperties,
                      self.srv.GetBodyPropertiesRequest(name=self.random.choice(self.bodies)),
                      expect=True)

    def motor(self):
        if not self.joints:
            return
        r = self.srv.SetJointMotorRequest(name=self.random.choice(self.joints)[0])
        r.speed, r.max_effort = self.random.uniform(-5, 5), self.random.uniform(0, 100)
        r.release = self.random.random() < 0.3
        self.call("set_joint_motor", self.srv.SetJointMotor, r, name=r.name)  # weld/distance: refused

    def spawn_model(self):
        if len(self.models) >= 4:  # devices are bounded per world (1024)
            return
        name = self.new_name("m")
        r = self.srv.SpawnModelRequest(model_name=name, model_yaml=MODEL_YAML)
        self.place(r.pose, 1.5)
        response = self.call("spawn_model", self.srv.SpawnModel, r, expect=True, name=name)
        if response is not None and response.success:
            self.models[name] = list(response.bodies)
            self.counts["models_made"] += 1

    def spawn_urdf(self):
        name = self.new_name("u")
        r = self.srv.SpawnUrdfRequest(model_name=name, urdf_xml=URDF_XML)
        self.place(r.pose, 1.5)
        response = self.call("spawn_urdf", self.srv.SpawnUrdf, r, expect=True, name=name)
        if response is not None and response.success:
            self.bodies.extend(response.bodies)
            self.counts["urdf_made"] += 1

    def move_model(self):
        if not self.models:
            return
        r = self.srv.MoveModelRequest(model_name=self.random.choice(sorted(self.models)))
        self.place(r.pose, 1.5)
        self.call("move_model", self.srv.MoveModel, r, expect=True, name=r.model_name)

    def delete_model(self):
        if not self.models:
            return
        name = self.random.choice(sorted(self.models))
        del self.models[name]
        self.call("delete_model", self.srv.DeleteModel, self.srv.DeleteModelRequest(model_name=name),
                  expect=True, name=name)

    def pause_step(self):
        self.call("pause", self.Empty, self.Empty._request_class())
        self.call("step", self.srv.Step, self.srv.StepRequest(steps=self.random.randint(1, 5)),
                  expect=True)
        self.call("unpause", self.Empty, self.Empty._request_class())

    def bad(self):
        m, srv = self.msg, self.srv
        kind = self.random.randrange(10)
        body = m.Body(name=self.new_name("bad"), type=m.Body.DYNAMIC, shapes=[self.shape()])
        if kind == 0:
            body.pose.x = float("nan")
            self.call("spawn_body", srv.SpawnBody, srv.SpawnBodyRequest(body=body), expect=False)
        elif kind == 1:
            body.shapes = [m.Shape(type=m.Shape.BOX, width=-1.0, height=0.5)]
            self.call("spawn_body", srv.SpawnBody, srv.SpawnBodyRequest(body=body), expect=False)
        elif kind == 2:  # a name taken (the arena's ground: one of ours may be gone by ~reset)
            body.name = "ground"
            self.call("spawn_body", srv.SpawnBody, srv.SpawnBodyRequest(body=body), expect=False)
        elif kind == 3:
            self.call("delete_body", srv.DeleteBody, srv.DeleteBodyRequest(name="no_such_body"),
                      expect=False)
        elif kind == 4 and self.bodies:
            r = srv.ApplyWrenchRequest(body=self.random.choice(self.bodies))
            r.force.x = float("inf")
            self.call("apply_wrench", srv.ApplyWrench, r, expect=False)
        elif kind == 5:
            j = m.Joint(name="c%d_badj" % self.index, type=m.Joint.REVOLUTE, body_a="no_such",
                        body_b="ground")
            self.call("create_joint", srv.CreateJoint, srv.CreateJointRequest(joint=j), expect=False)
        elif kind == 6:  # only .yaml files are read
            self.call("spawn_model", srv.SpawnModel,
                      srv.SpawnModelRequest(model_name="c%d_badm" % self.index, file="/etc/hostname"),
                      expect=False)
        elif kind == 7:  # not a model
            self.call("spawn_model", srv.SpawnModel,
                      srv.SpawnModelRequest(model_name="c%d_badm" % self.index,
                                            model_yaml="world: {gravity: [0, 0]}"),
                      expect=False)
        elif kind == 8:
            self.call("move_model", srv.MoveModel, srv.MoveModelRequest(model_name="no_such_model"),
                      expect=False)
        elif kind == 9:  # a URDF cut short
            self.call("spawn_urdf", srv.SpawnUrdf,
                      srv.SpawnUrdfRequest(model_name="c%d_bad" % self.index,
                                           urdf_xml=URDF_XML[:len(URDF_XML) // 2]), expect=False)

    def run(self):
        ops = [(0.20, self.spawn), (0.08, self.delete), (0.18, self.join), (0.05, self.unjoin),
               (0.07, self.teleport), (0.08, self.push), (0.15, self.read), (0.03, self.motor),
               (0.02, self.pause_step), (0.015, self.spawn_model), (0.02, self.move_model),
               (0.01, self.delete_model), (0.01, self.spawn_urdf), (0.085, self.bad)]
        while time.time() < self.deadline:
            self.sync_generation()
            if len(self.bodies) > 60:
                self.delete()
                continue
            pick, total = self.random.random(), 0.0
            for weight, op in ops:
                total += weight
                if pick < total:
                    op()
                    break

    def final_check(self, removed):
        """Every body still held is present, or was reported removed, and every dynamic one inside
        the arena (the kinematic bodies move too slowly to carry one out: see spawn, teleport)."""
        self.sync_generation()
        missing, outside = [], []
        for name in self.bodies + [b for bodies in self.models.values() for b in bodies]:
            r = self.proxy("get_body_state", self.srv.GetBodyState)(self.srv.GetBodyStateRequest(name=name))
            if not r.success and name not in removed:
                missing.append(name)
            elif r.success and name not in self.kinematic and not inside(r.pose, -ARENA_SLACK):
                outside.append("%s at (%.2f, %.2f)" % (name, r.pose.x, r.pose.y))
        if missing and not self.explained(""):
            self.fail("bodies gone without a report: %s" % missing[:10])
        if outside and not self.explained(""):
            self.fail("bodies outside the arena: %s" % outside[:10])
        return len(self.bodies)


def client_main(index, seed, ns, deadline, generation, removed_names, queue):
    import rospy
    rospy.init_node("soak_client_%d" % index, anonymous=True, disable_signals=True)
    client = Client(index, seed, ns, deadline, generation)
    try:
        client.run()
        checked = client.final_check(set(removed_names))
    except Exception:
        client.fail("crashed: " + traceback.format_exc(limit=3))
        checked = 0
    queue.put({"counts": client.counts, "failures": client.failures, "checked": checked})


def run_mode(mode, args, port):
    env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % port)
    os.environ["ROS_MASTER_URI"] = env["ROS_MASTER_URI"]
    name = "soak"
    launch = subprocess.Popen(["roslaunch", "-p", str(port), "impulse2d",
                               "soak_world.launch", "nodelet:=%s" % ("true" if mode == "nodelet" else "false")],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              start_new_session=True)
    cases = []  # (name, failure or None)
    try:
        import rospy
        from impulse2d import msg, srv
        from std_srvs.srv import Empty
        ns = "/" + name
        started = time.time()
        while True:
            try:
                rospy.wait_for_service(ns + "/get_body_state", timeout=1.0)
                break
            except Exception:
                if time.time() - started > 60:
                    raise RuntimeError("the world did not come up within 60 s")
        pattern = "__name:=%s_manager" % name if mode == "nodelet" else "impulse2d_node.*__name:=%s" % name
        pid = find_pid(pattern)
        # The clients first: rospy may be initialised once per process, and they fork from this one.
        generation = mp.Value("i", 0)
        manager = mp.Manager()
        removed_names = manager.list()
        queue = mp.Queue()
        deadline = time.time() + 2.0 + args.seconds
        clients = [mp.Process(target=client_main,
                              args=(i, args.seed, ns, deadline, generation, removed_names, queue))
                   for i in range(args.clients)]
        for c in clients:
            c.start()
        rospy.init_node("soak_controller", anonymous=True, disable_signals=True)
        seen = {"tf": 0, "markers": 0, "contacts": 0}
        removed = {"count": 0, "names": [], "reasons": []}

        def counter(key):
            def cb(_):
                seen[key] += 1
            return cb

        def on_removed(m):
            removed["count"] = m.count
            removed["names"] = [b.name for b in m.bodies]
            removed["reasons"] = ["%s (cause %d): %s" % (b.name, b.cause, b.reason) for b in m.bodies]

        from tf2_msgs.msg import TFMessage
        from visualization_msgs.msg import MarkerArray
        subs = [rospy.Subscriber("/tf", TFMessage, counter("tf")),
                rospy.Subscriber(ns + "/markers", MarkerArray, counter("markers")),
                rospy.Subscriber(ns + "/contacts", msg.ContactArray, counter("contacts")),
                rospy.Subscriber(ns + "/removed_bodies", msg.RemovedBodies, on_removed)]
        time.sleep(2.0)
        rss_start = rss_kib(pid) if pid else None
        # The controller: ~reset at a third, ~load_scene at two thirds.
        reset = rospy.ServiceProxy(ns + "/reset", Empty)
        load = rospy.ServiceProxy(ns + "/load_scene", srv.LoadScene)
        get = rospy.ServiceProxy(ns + "/get_body_state", srv.GetBodyState)
        events = []
        time.sleep(args.seconds / 3.0)
        with generation.get_lock():
            generation.value += 1
        t = time.monotonic()
        reset(); events.append(("reset", time.monotonic() - t))
        with generation.get_lock():
            generation.value += 1
        time.sleep(args.seconds / 3.0)
        t = time.monotonic()
        r = load(srv.LoadSceneRequest(yaml="bodies:\n  - {name: loaded_box, position: [0, 10], "
                                           "shapes: [{type: box, size: [0.5, 0.5]}]}\n"))
        events.append(("load_scene", time.monotonic() - t))
        load_ok = r.success and get(srv.GetBodyStateRequest(name="loaded_box")).success
        removed_names.extend(removed["names"])
        results = []
        for _ in clients:
            results.append(queue.get(timeout=args.seconds + 120))
        for c in clients:
            c.join(timeout=30)
        rss_end = rss_kib(pid) if pid else None
        alive = launch.poll() is None and get(srv.GetBodyStateRequest(name="ground")).success
        for s in subs:
            s.unregister()

        counts = {}
        failures = []
        for res in results:
            for k, v in res["counts"].items():
                counts[k] = max(counts.get(k, 0), v) if k == "slowest_ms" else counts.get(k, 0) + v
            failures += res["failures"]
        slow = [f for f in failures if " took " in f or " raised " in f]
        refused = [f for f in failures if "accepted" in f or "refused" in f]
        gone = [f for f in failures if "gone without" in f or "crashed" in f]
        outside = [f for f in failures if "outside the arena" in f]
        cases.append(("%s: every call answered within %.0f s" % (mode, SLOW_CALL), slow[0] if slow else None))
        cases.append(("%s: bad requests refused, valid ones accepted" % mode, refused[0] if refused else None))
        cases.append(("%s: no body removed" % mode,
                      None if removed["count"] == 0 else "%d removed: %s" % (removed["count"], removed["reasons"][:5])))
        cases.append(("%s: every body held is present" % mode, gone[0] if gone else None))
        cases.append(("%s: every dynamic body inside the arena" % mode, outside[0] if outside else None))
        slow_events = [e for e in events if e[1] > SLOW_CALL]
        cases.append(("%s: reset and load_scene mid-run" % mode,
                      None if load_ok and not slow_events else "load_ok=%s events=%s" % (load_ok, events)))
        growth = None if rss_start is None or rss_end is None else rss_end - rss_start
        cases.append(("%s: RSS bounded" % mode,
                      None if growth is not None and growth <= RSS_GROWTH_LIMIT
                      else "RSS %s -> %s KiB" % (rss_start, rss_end)))
        cases.append(("%s: the world alive at the end" % mode, None if alive else "the world is gone"))
        cases.append(("%s: topics flowing" % mode,
                      None if all(seen[k] > 0 for k in seen) else "received %s" % seen))
        print("ros soak %s seed %d: %d s, %d clients, %d calls (%d bad, refused; slowest %d ms), %d "
              "bodies, %d joints, %d models and %d URDF models made, %d removed, reset and load_scene %s, "
              "RSS %s -> %s KiB, messages %s"
              % (mode, args.seed, args.seconds, args.clients, counts.get("calls", 0),
                 counts.get("bad", 0) - counts.get("bad_accepted", 0), counts.get("slowest_ms", 0),
                 counts.get("bodies_made", 0),
                 counts.get("joints_made", 0), counts.get("models_made", 0), counts.get("urdf_made", 0),
                 removed["count"], events, rss_start, rss_end, seen),
              flush=True)
        for f in failures[:10]:
            print("  " + f, file=sys.stderr)
    except Exception:
        cases.append(("%s: the soak ran" % mode, traceback.format_exc(limit=5)))
    finally:
        try:
            os.killpg(launch.pid, signal.SIGINT)
            launch.wait(timeout=30)
        except Exception:
            os.killpg(launch.pid, signal.SIGKILL)
    return cases


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--clients", type=int, default=4)
    parser.add_argument("--mode", choices=["node", "nodelet", "both"], default="both")
    parser.add_argument("--junit")
    parser.add_argument("--port", type=int, default=11471)
    args = parser.parse_args()
    mp.set_start_method("fork")
    print("ros soak: seed %d, %g s per mode, %d clients" % (args.seed, args.seconds, args.clients),
          flush=True)
    cases = []
    if args.mode == "both":  # each mode in a process of its own (rospy initialises once)
        import tempfile
        import xml.etree.ElementTree as ET
        for i, mode in enumerate(["node", "nodelet"]):
            with tempfile.NamedTemporaryFile(suffix=".xml") as xml:
                subprocess.run([sys.executable, os.path.abspath(__file__), "--mode", mode,
                                "--seconds", str(args.seconds), "--seed", str(args.seed),
                                "--clients", str(args.clients), "--port", str(args.port + i),
                                "--junit", xml.name])
                try:
                    for case in ET.parse(xml.name).getroot().iter("testcase"):
                        failure = case.find("failure")
                        cases.append((case.get("name"),
                                      None if failure is None else failure.get("message")))
                except ET.ParseError:
                    cases.append(("%s: the soak ran" % mode, "no results"))
    else:
        cases = run_mode(args.mode, args, args.port)
    failed = [c for c in cases if c[1] is not None]
    for name, why in failed:
        if args.mode != "both":
            print("FAILED %s: %s (seed %d)" % (name, why, args.seed), file=sys.stderr)
    if args.junit:
        with open(args.junit, "w") as f:
            f.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="ros_soak" tests="%d" '
                    'failures="%d">\n' % (len(cases), len(failed)))
            for name, why in cases:
                f.write('  <testcase classname="ros_soak" name="%s"' % escape(name, {'"': "&quot;"}))
                f.write("/>\n" if why is None else
                        '><failure message="%s"/></testcase>\n' % escape(why[:2000], {'"': "&quot;"}))
            f.write("</testsuite>\n")
    if args.mode == "both":
        print("ros soak: %d checks, %d failed" % (len(cases), len(failed)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
