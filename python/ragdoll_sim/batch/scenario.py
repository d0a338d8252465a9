"""Scenario files of ragdoll_batch: load(path) reads and validates one (docs/batch.md).

The result is a plain dict (picklable, no open files) that runner.run_chunk takes. Every
refusal is a ScenarioError whose message names the field:
    scenario: push.size: expected a number or a distribution, got "big"
"""
import math
import os

import yaml


class ScenarioError(ValueError):
    """A scenario that cannot be run; str() is the one-line message naming the field."""


# Spawn pose and velocity of the root link: field -> default (m, rad, m/s, rad/s).
SPAWN_FIELDS = [("x", 0.0), ("y", 0.0), ("z", 1.1), ("roll", 0.0), ("pitch", 0.0), ("yaw", 0.0),
                ("vx", 0.0), ("vy", 0.0), ("vz", 0.0), ("wx", 0.0), ("wy", 0.0), ("wz", 0.0)]
# FallRecordDef fields a scenario may set (constants, >= 0): name -> default.
RECORD_FIELDS = {"rest_speed": 0.05, "rest_angular_speed": 0.5, "min_rest": 0.2}
MAX_PUSH = 1000.0  # N s: the scene's max_impulse
TOP_FIELDS = ["seed", "duration", "dt", "lanes", "world", "model", "spawn", "push", "material",
              "record"]


def package_dir():
    """The ragdoll_sim package folder (worlds/, urdf/): the source tree, else rospkg's path."""
    here = os.path.dirname(os.path.realpath(__file__))
    root = os.path.normpath(os.path.join(here, "..", "..", ".."))
    if os.path.isdir(os.path.join(root, "worlds")) and os.path.isdir(os.path.join(root, "urdf")):
        return root
    try:
        import rospkg
        return rospkg.RosPack().get_path("ragdoll_sim")
    except Exception:  # rospkg missing or the package not on ROS_PACKAGE_PATH
        return root


def _fail(field, message):
    raise ScenarioError("scenario: %s: %s" % (field, message))


def _show(value):
    """A value as the message quotes it: strings in double quotes, the rest as YAML writes it."""
    if isinstance(value, str):
        return '"%s"' % value
    return yaml.safe_dump(value, default_flow_style=True).strip().replace("\n...", "")


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _require_number(field, value, what="a number"):
    if not _number(value):
        _fail(field, "expected %s, got %s" % (what, _show(value)))
    return float(value)


def _distribution(field, value, lo=None, hi=None, text=False):
    """A validated distribution: a constant, or a one-key map uniform / normal / choice.

    lo, hi: the range every value must lie in (a normal's draws are clipped to it);
    text: values are strings (a link name), only constants and choices.
    """
    expected = "a name or a choice" if text else "a number or a distribution"

    def check(v, where):
        if text:
            if not isinstance(v, str) or not v:
                _fail(where, "expected a name, got %s" % _show(v))
            return v
        v = _require_number(where, v)
        if lo is not None and v < lo or hi is not None and v > hi:
            _fail(where, "%s is outside [%s, %s]" % (_show(v), _show(lo), _show(hi)))
        return v

    if isinstance(value, dict):
        if len(value) != 1:
            _fail(field, "expected %s (one of constant, uniform, normal, choice), got %s"
                  % (expected, _show(value)))
        kind, arg = next(iter(value.items()))
        where = "%s.%s" % (field, kind)
        if kind == "constant":
            return {"kind": "constant", "value": check(arg, where)}
        if kind == "choice":
            if not isinstance(arg, list) or not arg:
                _fail(where, "expected a non-empty list, got %s" % _show(arg))
            return {"kind": "choice",
                    "options": [check(v, "%s[%d]" % (where, i)) for i, v in enumerate(arg)]}
        if text:
            _fail(field, "expected %s, got %s" % (expected, _show(value)))
        if kind == "uniform":
            if not isinstance(arg, list) or len(arg) != 2:
                _fail(where, "expected [lo, hi], got %s" % _show(arg))
            a, b = check(arg[0], where + "[0]"), check(arg[1], where + "[1]")
            if a > b:
                _fail(where, "lo %s is above hi %s" % (_show(a), _show(b)))
            return {"kind": "uniform", "lo": a, "hi": b}
        if kind == "normal":
            if not isinstance(arg, dict) or set(arg) != {"mean", "std"}:
                _fail(where, "expected {mean: M, std: S}, got %s" % _show(arg))
            mean = _require_number(where + ".mean", arg["mean"])
            std = _require_number(where + ".std", arg["std"])
            if std < 0:
                _fail(where + ".std", "must be >= 0, got %s" % _show(std))
            return {"kind": "normal", "mean": mean, "std": std, "lo": lo, "hi": hi}
        _fail(field, "unknown distribution %s (expected constant, uniform, normal or choice)"
              % _show(kind))
    if text and isinstance(value, str) and value:
        return {"kind": "constant", "value": value}
    if not text and _number(value):
        return {"kind": "constant", "value": check(value, field)}
    _fail(field, "expected %s, got %s" % (expected, _show(value)))


def _map(field, value, known):
    if value is None:
        return {}
    if not isinstance(value, dict):
        _fail(field, "expected a map, got %s" % _show(value))
    for key in value:
        if key not in known:
            _fail("%s.%s" % (field, key) if field else str(key),
                  "unknown field (known: %s)" % ", ".join(known))
    return value


def _resolve_file(field, value, base, shipped_dir, suffix):
    """A path (relative to the scenario's folder) or a shipped name (shipped_dir/NAME + suffix)."""
    if not isinstance(value, str) or not value:
        _fail(field, "expected a name or a path, got %s" % _show(value))
    if os.sep not in value and not value.endswith(suffix):
        path = os.path.join(shipped_dir, value + suffix)
        if not os.path.isfile(path):
            names = sorted(f[:-len(suffix)] for f in os.listdir(shipped_dir) if f.endswith(suffix))
            _fail(field, "no shipped %s %s (shipped: %s; or give a path)"
                  % (field, _show(value), ", ".join(names)))
        return path
    path = value if os.path.isabs(value) else os.path.join(base, value)
    if not os.path.isfile(path):
        _fail(field, "no file %s" % _show(path))
    return os.path.abspath(path)


def validate(raw, base="."):
    """The validated scenario dict of a parsed YAML document; base: folder of relative paths."""
    if not isinstance(raw, dict):
        _fail("(top)", "expected a map of %s, got %s" % (", ".join(TOP_FIELDS), _show(raw)))
    top = _map("", raw, TOP_FIELDS)
    pkg = package_dir()
    out = {}
    seed = top.get("seed", 0)
    if not isinstance(seed, int) or isinstance(seed, bool) or not 0 <= seed < 2 ** 64:
        _fail("seed", "expected an integer in [0, 2^64), got %s" % _show(seed))
    out["seed"] = seed
    out["duration"] = _require_number("duration", top.get("duration", 3.0), "a number of seconds")
    if not 0 < out["duration"] <= 3600:
        _fail("duration", "must be in (0, 3600] s, got %s" % _show(out["duration"]))
    out["dt"] = _require_number("dt", top.get("dt", 0.001), "a number of seconds")
    if not 1e-5 <= out["dt"] <= 0.1:
        _fail("dt", "must be in [1e-05, 0.1] s, got %s" % _show(out["dt"]))
    lanes = top.get("lanes")  # None: the solver's default (SolverSettings::lanes)
    if lanes is not None and (not isinstance(lanes, int) or isinstance(lanes, bool)
                              or lanes not in (0, 1, 4, 8)):
        _fail("lanes", "expected 0 (float lanes, the widest, from 24 bodies), 1 (double rows), "
              "4 or 8, got %s" % _show(lanes))
    out["lanes"] = lanes
    world = top.get("world")
    out["world"] = None if world is None else _resolve_file(
        "world", world, base, os.path.join(pkg, "worlds"), ".world")
    model = top.get("model", "ragdoll")
    out["model"] = (os.path.join(pkg, "urdf", "ragdoll.urdf") if model == "ragdoll"
                    else _resolve_file("model", model, base, os.path.join(pkg, "urdf"), ".urdf"))

    spawn = _map("spawn", top.get("spawn"), [f for f, _ in SPAWN_FIELDS])
    out["spawn"] = {f: _distribution("spawn." + f, spawn.get(f, d)) for f, d in SPAWN_FIELDS}

    push = top.get("push")
    if push is None:
        out["push"] = None
    else:
        push = _map("push", push, ["link", "direction", "size"])
        if "link" not in push:
            _fail("push.link", "required: the link to push (e.g. torso)")
        direction = push.get("direction", [1.0, 0.0, 0.0])
        if not isinstance(direction, list) or len(direction) != 3:
            _fail("push.direction", "expected [x, y, z] (numbers or distributions), got %s"
                  % _show(direction))
        dist = [_distribution("push.direction[%d]" % i, v) for i, v in enumerate(direction)]
        if all(d["kind"] == "constant" and d["value"] == 0.0 for d in dist):
            _fail("push.direction", "must not be [0, 0, 0]")
        out["push"] = {
            "link": _distribution("push.link", push["link"], text=True),
            "direction": dist,
            "size": _distribution("push.size", push.get("size", 0.0), 0.0, MAX_PUSH),
        }

    material = _map("material", top.get("material"), ["friction", "restitution", "contact_hertz"])
    out["material"] = {
        "friction": _distribution("material.friction", material.get("friction", 0.8), 0.0, 100.0),
        "restitution": _distribution("material.restitution", material.get("restitution", 0.0),
                                     0.0, 1.0),
        "contact_hertz": _distribution("material.contact_hertz",
                                       material.get("contact_hertz", 0.0), 0.0, 1000.0),
    }

    record = _map("record", top.get("record"), list(RECORD_FIELDS) + ["torso_link"])
    out["record"] = {}
    for f, default in RECORD_FIELDS.items():
        v = _require_number("record." + f, record.get(f, default))
        if v < 0:
            _fail("record." + f, "must be >= 0, got %s" % _show(v))
        out["record"][f] = v
    torso = record.get("torso_link", "")
    if not isinstance(torso, str):
        _fail("record.torso_link", "expected a link name, got %s" % _show(torso))
    out["record"]["torso_link"] = torso
    return out


def load(path):
    """Reads and validates scenario file `path`; ScenarioError naming the field when refused."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise ScenarioError("scenario: %s: %s" % (path, e.strerror or e))
    try:
        raw = yaml.safe_load(text)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = " line %d" % (mark.line + 1) if mark else ""
        raise ScenarioError("scenario: %s%s: not YAML (%s)"
                            % (path, where, getattr(e, "problem", None) or e))
    return validate(raw, os.path.dirname(os.path.abspath(path)))
