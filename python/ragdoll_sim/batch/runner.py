"""One row per run: run i of a scenario is a pure function of (scenario, i).

run_chunk(scenario, indices) -> list of row dicts (keys = columns(scenario), in order) is what
the Dask fan-out (fanout.py) sends to its workers; `ragdoll_batch run --workers 1` calls it
in-process. The model and world files are parsed once per process (cached by path).
"""
import math

from . import sampling

PARAMETER_COLUMNS = (["spawn_" + f for f in ("x", "y", "z", "roll", "pitch", "yaw",
                                             "vx", "vy", "vz", "wx", "wy", "wz")]
                     + ["push_link", "push_size", "push_dx", "push_dy", "push_dz",
                        "friction", "restitution", "contact_hertz"])
REST_COLUMNS = ["rest_class", "rest_x", "rest_y", "rest_z", "rest_roll", "rest_pitch", "rest_yaw"]
TAIL_COLUMNS = ["broken_joints", "time_to_rest", "nan"]

_models = {}
_worlds = {}


def _core():
    from .. import _core as core  # the compiled module, imported when a run needs it
    return core


def model(path):
    """The Model of URDF file `path`, read once per process."""
    if path not in _models:
        _models[path] = _core().Model.from_file(path)
    return _models[path]


def world(path):
    """The WorldFile of world file `path` (None: no world), read once per process."""
    if path is None:
        return None
    if path not in _worlds:
        _worlds[path] = _core().WorldFile.from_file(path)
    return _worlds[path]


def force_column(link):
    """The CSV column of a link's peak contact force."""
    return "force_" + link


def columns(scenario):
    """The CSV columns of a scenario's rows, in order (one force column per model link)."""
    links = model(scenario["model"]).link_names
    return (["index"] + PARAMETER_COLUMNS + REST_COLUMNS + ["head_peak_g", "hic15"]
            + [force_column(l) for l in links] + TAIL_COLUMNS)


def check(scenario):
    """Problems only the model can tell, as 'field: message' strings (the push's link names)."""
    push = scenario["push"]
    if push is None:
        return []
    links = model(scenario["model"]).link_names
    spec = push["link"]
    names = spec["options"] if spec["kind"] == "choice" else [spec["value"]]
    return ['push.link: the model has no link "%s" (links: %s)' % (n, ", ".join(links))
            for n in names if n not in links]


def _value(spec, draws, name):
    v = sampling.draw(spec, draws, name)
    if spec["kind"] == "normal":  # clipped to the field's range
        if spec.get("lo") is not None:
            v = max(v, spec["lo"])
        if spec.get("hi") is not None:
            v = min(v, spec["hi"])
    return v


def parameters(scenario, index):
    """The drawn parameters of run `index`: a dict of PARAMETER_COLUMNS."""
    draws = sampling.Draws(scenario["seed"], index)
    out = {}
    for f, spec in scenario["spawn"].items():
        out["spawn_" + f] = float(_value(spec, draws, "spawn." + f))
    push = scenario["push"]
    if push is None:
        out.update(push_link="", push_size=0.0, push_dx=0.0, push_dy=0.0, push_dz=0.0)
    else:
        d = [float(_value(s, draws, "push.direction[%d]" % i))
             for i, s in enumerate(push["direction"])]
        n = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        if n == 0.0:
            raise ValueError("run %d: push.direction drew [0, 0, 0]" % index)
        out["push_link"] = _value(push["link"], draws, "push.link")
        out["push_size"] = float(_value(push["size"], draws, "push.size"))
        out["push_dx"], out["push_dy"], out["push_dz"] = d[0] / n, d[1] / n, d[2] / n
    for f, spec in scenario["material"].items():
        out[f] = float(_value(spec, draws, "material." + f))
    return out


def _record_def(scenario):
    core = _core()
    d = core.FallRecordDef()
    for k, v in scenario["record"].items():
        setattr(d, k, v)
    return d


def run_one(scenario, index):
    """The row dict of run `index` (keys = columns(scenario), in order)."""
    p = parameters(scenario, index)
    size = p["push_size"]
    # a scenario without lanes takes run_fall's default, the solver's
    lanes = {} if scenario["lanes"] is None else {"lanes": scenario["lanes"]}
    rec = _core().run_fall(
        model(scenario["model"]), world(scenario["world"]),
        position=(p["spawn_x"], p["spawn_y"], p["spawn_z"]),
        rpy=(p["spawn_roll"], p["spawn_pitch"], p["spawn_yaw"]),
        linear_velocity=(p["spawn_vx"], p["spawn_vy"], p["spawn_vz"]),
        angular_velocity=(p["spawn_wx"], p["spawn_wy"], p["spawn_wz"]),
        push_link=p["push_link"] if size > 0.0 else "",
        push_impulse=(size * p["push_dx"], size * p["push_dy"], size * p["push_dz"]),
        friction=p["friction"], restitution=p["restitution"],
        contact_hertz=p["contact_hertz"], dt=scenario["dt"],
        steps=int(round(scenario["duration"] / scenario["dt"])), record=_record_def(scenario),
        **lanes)
    row = {"index": index}
    row.update(p)
    pos = rec.root_position
    row.update(rest_class=rec.rest_class, rest_x=pos[0], rest_y=pos[1], rest_z=pos[2],
               rest_roll=rec.roll, rest_pitch=rec.pitch, rest_yaw=rec.yaw,
               head_peak_g=rec.head_peak_g, hic15=rec.hic15)
    for link, f in zip(rec.links, rec.peak_contact_force):
        row[force_column(link)] = f
    row.update(broken_joints=";".join(rec.broken_joints), time_to_rest=rec.time_to_rest,
               nan=int(rec.nan))
    return {c: row[c] for c in columns(scenario)}


def run_chunk(scenario, indices):
    """Rows of runs `indices`, in that order: a pure function of (scenario, index) each."""
    return [run_one(scenario, int(i)) for i in indices]
