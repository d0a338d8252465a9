"""ragdoll_sim.Scene from Python: closed forms, errors with the core's messages, determinism,
array shapes and the help text. Runs after `source devel/setup.bash` (ragdoll_add_pytest)."""
import math
import pathlib
import pydoc

import numpy as np
import pytest

import ragdoll_sim

ROOT = pathlib.Path(__file__).resolve().parents[2]
RAGDOLL_URDF = str(ROOT / "urdf" / "ragdoll.urdf")
STAIRS_WORLD = str(ROOT / "worlds" / "stairs.world")
G = 9.81

# One 2 kg box link, 0.2 m cube, its centre of mass at the link origin.
BOX_URDF = """<robot name="box">
  <link name="base">
    <inertial><mass value="2.0"/><origin xyz="0 0 0"/>
      <inertia ixx="0.0133" iyy="0.0133" izz="0.0133" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
</robot>"""


@pytest.fixture(scope="module")
def box():
    return ragdoll_sim.Model.from_string(BOX_URDF)


@pytest.fixture(scope="module")
def ragdoll():
    return ragdoll_sim.Model.from_file(RAGDOLL_URDF)


def test_free_fall_matches_closed_form(box):
    scene = ragdoll_sim.Scene(dt=0.001, ground=False)
    scene.spawn("box", box, position=(0, 0, 10))
    scene.step(500)
    t = scene.time
    assert t == pytest.approx(0.5, abs=1e-12)
    assert scene.steps == 500
    z = scene.link_poses("box")[0, 2]
    vz = scene.link_velocities("box")[0, 2]
    assert vz == pytest.approx(-G * t, rel=1e-9)
    # Semi-implicit Euler leads the exact parabola by at most one step's g dt t.
    assert abs(z - (10 - 0.5 * G * t * t)) <= G * scene.dt * t
    assert z < 10 - 0.5 * G * t * t + 1e-12


def test_impulse_changes_velocity_by_j_over_m(box):
    scene = ragdoll_sim.Scene(ground=False, gravity=(0, 0, 0))
    scene.spawn("box", box, position=(0, 0, 1))
    scene.apply_impulse("box", "base", (3.0, -1.0, 0.5))
    v = scene.link_velocities("box")[0]
    np.testing.assert_allclose(v[:3], np.array([3.0, -1.0, 0.5]) / box.mass, rtol=1e-12)
    np.testing.assert_allclose(v[3:], 0.0, atol=1e-12)  # at the centre of mass: no spin
    scene.step(100)
    np.testing.assert_allclose(scene.link_velocities("box")[0, :3], [1.5, -0.5, 0.25], rtol=1e-9)
    np.testing.assert_allclose(scene.link_poses("box")[0, :3], [0.15, -0.05, 1.025], rtol=1e-9)


def test_resting_box_contacts_carry_its_weight(box):
    scene = ragdoll_sim.Scene(sleep=False)
    scene.spawn("box", box, position=(0, 0, 0.1))
    scene.step(500)
    c = scene.contacts()
    on_box = (c["body_b"] == "box/base")
    under_box = (c["body_a"] == "box/base")
    assert on_box.any() or under_box.any()
    lift = c["force"][on_box, 2].sum() - c["force"][under_box, 2].sum()
    assert lift == pytest.approx(box.mass * G, rel=1e-3)
    assert np.all(c["normal_force"] >= 0)


def test_contact_and_link_arrays_have_documented_shapes(ragdoll):
    scene = ragdoll_sim.Scene()
    scene.spawn("r", ragdoll, position=(0, 0, 1.0))
    scene.step(300)
    n = len(scene.link_names("r"))
    assert n == len(ragdoll.link_names) > 10
    poses, vels = scene.link_poses("r"), scene.link_velocities("r")
    assert poses.shape == (n, 7) and poses.dtype == np.float64
    assert vels.shape == (n, 6) and vels.dtype == np.float64
    np.testing.assert_allclose(np.linalg.norm(poses[:, 3:], axis=1), 1.0, atol=1e-9)
    assert scene.link_coms("r").shape == (n, 3)
    efforts = scene.joint_efforts("r")
    assert efforts.shape == (len(scene.joint_names("r")),) and efforts.dtype == np.float64
    c = scene.contacts()
    k = len(c["depth"])
    assert k > 0
    assert c["point"].shape == c["normal"].shape == c["force"].shape == (k, 3)
    assert c["normal_force"].shape == (k,) and c["body_a"].shape == c["body_b"].shape == (k,)
    assert all(name.startswith("r/") or name == "ground"
               for name in np.concatenate([c["body_a"], c["body_b"]]))


def test_pushed_ragdoll_gets_injury_record_and_impacts(ragdoll):
    scene = ragdoll_sim.Scene(impacts=True)
    scene.spawn("r", ragdoll, position=(0, 0, 1.3))
    scene.apply_impulse("r", "head", (25.0, 0, 0))
    scene.step(1000)
    rep = scene.injury("r")
    assert rep.head_link == "head"
    assert rep.peak_g > 1.0 and rep.hic15 > 0.0 and rep.hic36 >= rep.hic15
    assert set(rep.to_dict()) >= {"peak_g", "hic15", "hic36", "peak_neck_force"}
    hits = scene.impacts()
    assert len(hits["time"]) > 0 and set(hits["ragdoll"]) == {"r"}
    assert hits["point"].shape == (len(hits["time"]), 3)


def test_world_file_loads_and_models_spawn_on_it(ragdoll, box):
    scene = ragdoll_sim.Scene()
    summary = scene.load_world(STAIRS_WORLD)
    assert "status=ok" in summary
    scene.spawn("r", ragdoll, position=(-2, 0, 1.5), rpy=(0, 0, math.pi / 2))
    scene.spawn("crate", box, position=(3, 2, 0.5), object=True)
    assert scene.names == ["r", "crate"] and scene.is_object("crate")
    scene.step(200)
    scene.remove("crate")
    assert scene.names == ["r"]
    h = scene.state_hash()  # the removed bodies' slots are skipped
    scene.step(10)
    assert scene.state_hash() != h


def test_spawn_velocity_and_efforts(ragdoll, box):
    scene = ragdoll_sim.Scene(ground=False, gravity=(0, 0, 0))
    scene.spawn("box", box, position=(0, 0, 1), linear_velocity=(1, 2, 3))
    np.testing.assert_allclose(scene.link_velocities("box")[0, :3], [1, 2, 3], rtol=1e-12)
    scene.spawn("r", ragdoll, position=(5, 0, 1))
    joint = scene.joint_names("r")[0]
    scene.apply_joint_efforts("r", {joint: 5.0}, duration=0.01)
    scene.apply_force("r", "pelvis", (0, 0, 10.0), duration=0.01)
    scene.step(5)
    assert scene.counters()["applied"] == 2
    assert scene.clear_forces() >= 1


def _hash_after(model, push, threads=1, lanes=1):
    scene = ragdoll_sim.Scene(threads=threads, lanes=lanes)
    scene.spawn("r", model, position=(0, 0, 1.2))
    scene.apply_impulse("r", "head", push)
    scene.step(300)
    return scene.state_hash()


def test_identical_scenes_hash_equal_and_a_different_push_differs(ragdoll):
    h = _hash_after(ragdoll, (20.0, 0, 0))
    assert isinstance(h, int) and 0 <= h < 2**64
    assert _hash_after(ragdoll, (20.0, 0, 0)) == h
    assert _hash_after(ragdoll, (20.0, 0, 0), threads=2) == h
    assert _hash_after(ragdoll, (20.0, 1e-9, 0)) != h


def test_lane_widths_agree_and_a_lone_ragdoll_takes_the_double_rows(ragdoll):
    assert ragdoll_sim.Scene(lanes=1).lane_width == 1
    widest = ragdoll_sim.Scene(lanes=0).lane_width
    assert widest in (4, 8)
    assert ragdoll_sim.Scene().lane_width == widest  # the float lanes by default
    assert ragdoll_sim.Scene(lanes=4).lane_width == 4
    h = _hash_after(ragdoll, (20.0, 0, 0), lanes=4)
    assert _hash_after(ragdoll, (20.0, 0, 0), lanes=8) == h
    assert _hash_after(ragdoll, (20.0, 0, 0), lanes=4, threads=2) == h
    # float rows round otherwise than double ones: another trajectory, not the same bits
    double = _hash_after(ragdoll, (20.0, 0, 0), lanes=1)
    assert double != h
    # lanes=0 runs the lanes from 24 awake bodies: a lone ragdoll's 15 take the double rows
    assert _hash_after(ragdoll, (20.0, 0, 0), lanes=0) == double


def test_errors_name_the_problem_and_change_nothing(ragdoll, box):
    scene = ragdoll_sim.Scene()
    scene.spawn("r", ragdoll, position=(0, 0, 1.2))
    scene.step(10)
    h = scene.state_hash()
    with pytest.raises(ValueError, match="nobody"):
        scene.link_poses("nobody")
    with pytest.raises(ValueError, match="nobody"):
        scene.apply_impulse("nobody", "head", (1, 0, 0))
    with pytest.raises(ValueError, match="no link 'nose'"):
        scene.apply_impulse("r", "nose", (1, 0, 0))
    with pytest.raises(ValueError, match="tail_joint"):
        scene.apply_joint_efforts("r", {"tail_joint": 1.0})
    with pytest.raises(ValueError, match="impulse"):
        scene.apply_impulse("r", "head", (1e6, 0, 0))
    with pytest.raises(ValueError, match="frame"):
        scene.apply_impulse("r", "head", (1, 0, 0), frame="moon")
    with pytest.raises(ValueError, match="'r'"):
        scene.spawn("r", ragdoll, position=(3, 0, 1.2))
    with pytest.raises(ValueError, match="position"):
        scene.spawn("s", ragdoll, position=(0, 0, float("nan")))
    with pytest.raises(ValueError, match="position must have 3"):
        scene.spawn("s", ragdoll, position=(0, 0))
    with pytest.raises(ValueError, match="orientation"):
        scene.spawn("s", ragdoll, position=(0, 0, 1), orientation=(0, 0, 0, 0))
    with pytest.raises(ValueError, match="not both"):
        scene.spawn("s", ragdoll, orientation=(0, 0, 0, 1), rpy=(0, 0, 0))
    with pytest.raises(ValueError, match="n must be >= 0"):
        scene.step(-1)
    with pytest.raises(ValueError, match="crate"):
        scene.remove("crate")
    with pytest.raises(ValueError, match="no head link"):
        box_scene = ragdoll_sim.Scene()
        box_scene.spawn("box", box, position=(0, 0, 0.5))
        box_scene.injury("box")
    with pytest.raises(RuntimeError, match="missing.urdf"):
        ragdoll_sim.Model.from_file(str(ROOT / "missing.urdf"))
    with pytest.raises(RuntimeError):
        ragdoll_sim.Model.from_string("<robot name='x'><link name=")
    with pytest.raises(RuntimeError, match="missing.world"):
        scene.load_world(str(ROOT / "missing.world"))
    with pytest.raises(ValueError, match="dt"):
        ragdoll_sim.Scene(dt=0)
    with pytest.raises(ValueError, match="threads"):
        ragdoll_sim.Scene(threads=-3)
    with pytest.raises(ValueError, match="lanes must be 0 .*got 2"):
        ragdoll_sim.Scene(lanes=2)
    assert scene.names == ["r"] and scene.steps == 10
    assert scene.state_hash() == h
    scene.step(10)
    assert np.isfinite(scene.link_poses("r")).all()


def test_help_describes_every_method():
    text = pydoc.render_doc(ragdoll_sim.Scene, renderer=pydoc.plaintext)
    for method in ("spawn", "remove", "load_world", "apply_impulse", "apply_force",
                   "apply_joint_efforts", "step", "link_poses", "link_velocities", "contacts",
                   "impacts", "injury", "state_hash"):
        assert method + "(" in text, method
    assert "position" in text and "ValueError" in text and "x y z qx qy qz qw" in text
    for name in dir(ragdoll_sim.Scene):
        if not name.startswith("_"):
            assert getattr(ragdoll_sim.Scene, name).__doc__, name


def _fnv1a(h, data):
    for byte in data:
        h = ((h ^ byte) * 1099511628211) % 2**64
    return h


def test_state_hash_is_fnv1a_of_every_body_state(box):
    """The documented definition, recomputed here: the ground body first, then the box (its
    centre of mass at the link origin, so link and body velocities agree)."""
    import struct
    scene = ragdoll_sim.Scene(gravity=(0, 0, -9.81))
    scene.spawn("box", box, position=(0.1, -0.2, 2.0), rpy=(0.1, 0.2, 0.3),
                linear_velocity=(0.5, 0, 0), angular_velocity=(0, 0, 1.0))
    scene.step(50)
    x, y, z, qx, qy, qz, qw = scene.link_poses("box")[0]
    v = scene.link_velocities("box")[0]
    offset = 14695981039346656037
    h = _fnv1a(offset, struct.pack("<13d", 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0))  # ground
    h = _fnv1a(h, struct.pack("<13d", x, y, z, qw, qx, qy, qz, *v))
    assert scene.state_hash() == h
    assert scene.state_hash(seed=offset) == h
    assert scene.state_hash(seed=5) != h
    with pytest.raises(ValueError, match="seed"):
        scene.state_hash(seed=-1)
