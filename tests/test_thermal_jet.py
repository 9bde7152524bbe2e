"""`bearing thermal` with an oil supply: a jet-lubricated 35-mm bore angular-contact bearing under the
conditions of NASA's high-speed tests (ester oil at 394 K inlet, 0.76 L/min, light thrust, 28,000 rpm)
reaches a thermal steady state -- no runaway -- with the cavity oil content taken from the jet flow."""
import json

from bearing_core.bearing.catalogue import catalogue_definition
from bearing_core.cli import main


def test_jet_lubricated_35mm_bearing_holds_at_28000_rpm(tmp_path, capsys):
    d = catalogue_definition("7207AC")          # 35 x 72 x 17 mm, internal geometry estimated
    d.update(name="acbb-35mm-class", bore_diameter_mm=35.0, outside_diameter_mm=72.0)
    f = tmp_path / "acbb35.json"
    f.write_text(json.dumps(d))
    rc = main(["thermal", "--bearing", str(f), "--speed-rpm", "28000", "--fz", "667", "--oil", "mil-prf-23699-ester",
               "--oil-inlet-c", "120.85", "--oil-flow-lpm", "0.76", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["thermal_runaway"] is False, out
    assert out["lubrication_method"] == "jet" and out["cavity_oil"]["method"] == "jet"
    assert 0.0 < out["oil_fraction"] < 0.01 and not out["cavity_oil"]["extrapolated"]
    T_in = out["oil_inlet_temperature_K"]
    for node, T in out["temperatures_K"].items():          # above the inlet, far below the 473 K oil limit
        assert T_in < T < T_in + 50.0, (node, T)
    assert abs(out["heat_balance"]) < 0.02
    assert out["heat_to_oil_flow_W"] > 0.4 * out["heat_generated_W"]    # jet cooling carries much of the heat


def test_bad_supply_input_names_parameter(capsys):
    rc = main(["thermal", "--bearing", "7218B", "--speed-rpm", "3000", "--fz", "1000",
               "--lubrication-method", "bath"])
    assert rc == 2
    assert "oil_level" in capsys.readouterr().err
