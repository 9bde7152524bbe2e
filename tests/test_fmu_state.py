"""The serialised FMU state (fmi2SerializeFMUstate / fmi2DeSerializeFMUstate) is plain data: a versioned,
length-checked binary format of the slave's variables and the session's rollback state, checked field by
field against the instance; bytes from a master are never unpickled."""
import json
import os
import pickle
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "bearing_cosim" / "fmu_src" / "native"))
sys.path.insert(0, str(HERE.parent / "bearing_cosim" / "fmu_src"))
import model_process as mp  # noqa: E402


class _Evil:
    """Unpickling this would create the file named by PATH."""
    PATH = ""

    def __reduce__(self):
        return (os.system, (f"touch {self.PATH}",))


@pytest.fixture(scope="module")
def models():
    """Initialised models (the checks and modes of the model process around the slave) at the dynamic and the
    quasi-static fidelity level, one 1 ms step each."""
    from bearing_fmu import BearingFMU
    out = {}
    for fid in ("dynamic", "quasi-static"):
        m = mp.Model(BearingFMU, "t", False, False, None)
        m.guid = "{guid-of-this-build}"
        m.slave.fidelity = fid
        m.setup(0, 0.0, 0.0, 0.0, 0)
        m.enter()
        m.exit()
        assert m.step(0.0, 1e-3) == mp.OK
        out[fid] = m
    return out


@pytest.mark.parametrize("fid", ["dynamic", "quasi-static"])
def test_round_trip_repeats_the_step_bit_for_bit(models, fid):
    """A state serialised and deserialised (a new state) repeats the next step bit for bit."""
    m = models[fid]
    sid = m.get_state(0)
    data = m.serialize(sid)
    assert data[:8] == b"BRGSTATE" and b"\x80\x04" not in data[:16]
    assert m.step(1e-3, 1e-3) == mp.OK
    a = np.array(m.slave._out, copy=True)
    sid2 = m.deserialize(data, 0)
    assert sid2 != sid
    m.set_state(sid2)
    assert m.step(1e-3, 1e-3) == mp.OK
    assert np.array_equal(np.array(m.slave._out), a)


def _fields(m):
    return mp.decode_state(m.serialize(m.get_state(0)))


def test_refusals_name_the_field(models, tmp_path):
    """Wrong GUID, format version, truncated body, a 4 GB count, unknown tags, a variable of the wrong type or
    outside its range, a session array of the wrong shape or dtype, a pickle: each refused with FmiError
    naming what is wrong; a crafted pickle that would create a file creates none."""
    m = models["dynamic"]
    good = m.serialize(m.get_state(0))

    def refused(data, match):
        with pytest.raises(mp.FmiError, match=match):
            m.deserialize(data, 0)

    _Evil.PATH = str(tmp_path / "pwned")
    refused(pickle.dumps(_Evil()), "not a serialized state of this FMU")
    refused(pickle.dumps((2, {"x": _Evil()})), "not a serialized state")
    assert not (tmp_path / "pwned").exists()
    refused(good[:8] + struct.pack("<I", 99) + good[12:], "format version 99; this FMU reads version 1")
    refused(good[:-5], "body length")
    body = good[16:]
    refused(good[:12] + struct.pack("<I", len(body) - 3) + body[:-3], "truncated|exceeds the remaining")
    refused(mp.encode_state({})[:12] + struct.pack("<I", 5) + b"m\xff\xff\xff\xff", "count of 4294967295")
    refused(mp.encode_state({})[:12] + struct.pack("<I", 1) + b"p", "unknown tag")
    st = _fields(m)

    def with_(**kw):
        s = dict(st, slave=dict(st["slave"]))
        for k, v in kw.items():
            if k in ("guid", "mode", "time"):
                s[k] = v
            else:
                s["slave"][k] = v
        return mp.encode_state(s)

    refused(with_(guid="{other}"), r"GUID '\{other\}'; this FMU is \{guid-of-this-build\}")
    refused(with_(mode="failed"), "mode = 'failed' is invalid")
    refused(with_(time=float("nan")), "time = nan is invalid")
    refused(with_(friction_coefficient="0.1"), "friction_coefficient = '0.1' is a str; allowed: a Real")
    refused(with_(friction_coefficient=7.0), r"friction_coefficient = 7.0 is outside the allowed range \[0, 1\]")
    refused(with_(fidelity_choice=9), "fidelity_choice = 9 is not an item value")
    refused(with_(__class__=1), "unknown: __class__")
    sess = list(st["slave"]["_session_state"])
    sess[0] = sess[0][:-1]
    refused(with_(_session_state=tuple(sess)), r"session state\[0\] is an array of float64 \(163,\); allowed: an "
                                               r"array of float64 \(164,\)")
    sess = list(st["slave"]["_session_state"])
    sess[2] = sess[2].astype(np.int64)
    refused(with_(_session_state=tuple(sess)), r"session state\[2\] is an array of int64")
    refused(with_(_session_state=("steady", (0.0,))), r"session state is tuple of 2 items; allowed: 8 items")
    # still usable, and the good bytes still restore
    m.set_state(m.deserialize(good, 0))
    assert m.step(m.time, 1e-3) == mp.OK


def test_crafted_pickle_refused_through_fmpy(tmp_path_factory, tmp_path):
    """Through the FMU in fmpy: a pickle that would create a file, given to fmi2DeSerializeFMUstate, is
    fmi2Error with the reason logged, no file appears, and the instance steps on (OK)."""
    sys.path.insert(0, str(HERE))
    from test_native_host import _cache
    from build_fmu import build
    fmu = build(tmp_path_factory.mktemp("state") / "dist")
    target = tmp_path / "pwned"
    _Evil.PATH = str(target)
    (tmp_path / "evil.bin").write_bytes(pickle.dumps((2, {"x": _Evil()}), protocol=4))
    code = r"""
import json, sys
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi1 import FMICallException
md = read_model_description(sys.argv[1])
logs = []
f = FMU2Slave(guid=md.guid, unzipDirectory=extract(sys.argv[1]), modelIdentifier="BearingFMU", instanceName="a")
f.instantiate(loggingOn=False)
f.setupExperiment(startTime=0.0); f.enterInitializationMode(); f.exitInitializationMode()
out = {}
try:
    f.deSerializeFMUstate(open(sys.argv[2], "rb").read()); out["deser"] = 0
except FMICallException as e:
    out["deser"] = e.status
f.doStep(0.0, 1e-3); out["step"] = 0
f.terminate(); f.freeInstance()
print("RESULT", json.dumps(out))
"""
    r = subprocess.run([sys.executable, "-c", code, str(fmu), str(tmp_path / "evil.bin")], capture_output=True,
                       text=True, env=dict(os.environ, BEARING_FMU_CACHE=_cache(tmp_path_factory)), timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout.split("RESULT", 1)[1])
    assert out == {"deser": 3, "step": 0}
    assert "fmi2DeSerializeFMUstate: not a serialized state of this FMU" in r.stdout + r.stderr
    assert not target.exists()
