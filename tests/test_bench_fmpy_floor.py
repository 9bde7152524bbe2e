"""bench/fmpy_floor.py: the do-nothing FMU it measures the master's own cost with is a working FMI 2.0
co-simulation FMU for fmpy (its calls reach the C functions and return what they set); no timing assertions."""
import importlib.util
import os
import shutil
from pathlib import Path

import pytest


def _bench():
    path = Path(__file__).resolve().parents[1] / "bench" / "fmpy_floor.py"
    spec = importlib.util.spec_from_file_location("bench_fmpy_floor", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.skipif(shutil.which(os.environ.get("CC", "gcc")) is None, reason="needs a C compiler")
def test_do_nothing_fmu_runs_in_fmpy(tmp_path):
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    b = _bench()
    fmu = b.build(tmp_path)
    md = read_model_description(str(fmu))
    assert md.coSimulation.modelIdentifier == "Floor"
    names = {v.name: v.valueReference for v in md.modelVariables}
    assert [names[f"u{k}"] for k in range(b.N_IN)] == list(range(b.N_IN))
    f = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)), modelIdentifier="Floor", instanceName="t")
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    f.exitInitializationMode()
    f.setReal([0, 1, 7], [1.5, -2.0, 3.25])
    f.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    assert f.getReal([0, 1, 7]) == [1.5, -2.0, 3.25]
    assert f.getRealStatus(2) == pytest.approx(1e-3)        # fmi2LastSuccessfulTime
    f.terminate()
    f.freeInstance()
    r = b.floor_per_sim_s(fmu, 0.2, 10)
    assert r["wall_per_sim_s"] > 0.0 and r["doStep_per_sim_s"] > 0.0 and r["outputs_read"] == 10


def test_do_nothing_slave_runs_on_the_bearing_fmu_layer(tmp_path, monkeypatch):
    """The second floor: a pythonfmu slave that does nothing, on the bearing FMU's native layer and model process,
    takes its inputs and steps through fmpy (an instance's model in its own process)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    monkeypatch.setenv("BEARING_FMU_CACHE", str(tmp_path / "cache"))
    b = _bench()
    fmu = b.build_idle(tmp_path)
    md = read_model_description(str(fmu))
    ins = [v.valueReference for v in md.modelVariables if v.causality == "input"]
    outs = [v.valueReference for v in md.modelVariables if v.causality == "output"]
    assert len(ins) == b.N_IN and len(outs) == b.N_VARS - b.N_IN
    f = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(fmu)), modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="t")
    f.instantiate()
    f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    f.exitInitializationMode()
    f.setReal(ins, [1.0, 2.0, 3.0])
    f.doStep(currentCommunicationPoint=0.0, communicationStepSize=1e-3)
    assert f.getReal(ins) == [1.0, 2.0, 3.0] and f.getReal(outs) == [0.0] * len(outs)
    f.terminate()
    f.freeInstance()
    r = b.floor_per_sim_s(fmu, 0.2, 10)
    assert r["wall_per_sim_s"] > 0.0 and r["doStep_per_sim_s"] > 0.0
