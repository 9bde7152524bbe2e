"""Write SSP 1.0 archives (SystemStructure.ssd + resources/*.fmu) that both fmpy's SSP reader and libcosim's
SSP loader accept. Small on purpose: components, typed connectors with units, connections, inline ParameterBindings
(ssv ParameterSet) and a DefaultExperiment carrying the Open Simulation Platform's fixed-step annotation.

What the two readers need (read from their sources, fmpy 0.3.32 fmpy/ssp/ssd.py and libcosim src/cosim/ssp/):
* fmpy validates the SSD against the SSP 1.0 XML schema and requires every declared *input* connector to be
  connected (its get_connections looks each one up); libcosim requires a type element (ssc:Real ...) on every
  connector and a ``source`` on every element.
* libcosim takes the master step from ``DefaultExperiment/Annotations/Annotation[@type=com.opensimulationplatform]/
  osp:Algorithm/osp:FixedStepAlgorithm@baseStepSize``; the SSD 1.0 schema has no standard element for it. Our
  fmpy runner (ssp_examples/masters.py) reads the same attribute.
* Parameter names in a component's ParameterBinding are the FMU variable names (SSP 1.0: relative to the
  component). libcosim applies them as start values (parameters and inputs); fmpy's simulate_ssp ignores the
  SSD's bindings, so masters.py hands them to it as a ParameterSet with component-prefixed names.
"""
from __future__ import annotations

import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from xml.sax.saxutils import quoteattr

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations",
}
# SI base-unit exponents of the units used by the examples (kg, m, s, rad)
UNITS = {
    "m": dict(m=1), "m/s": dict(m=1, s=-1), "m/s2": dict(m=1, s=-2), "rad": dict(rad=1), "rad/s": dict(rad=1, s=-1),
    "rad/s2": dict(rad=1, s=-2), "N": dict(kg=1, m=1, s=-2), "N.m": dict(kg=1, m=2, s=-2), "W": dict(kg=1, m=2, s=-3),
    "J": dict(kg=1, m=2, s=-2), "kg": dict(kg=1), "kg.m2": dict(kg=1, m=2), "N/m": dict(kg=1, s=-2),
    "N.s/m": dict(kg=1, s=-1), "N.m.s/rad": dict(kg=1, m=2, s=-1, rad=-1), "s": dict(s=1), "1": dict(),
    "Pa": dict(kg=1, m=-1, s=-2),
}


@dataclass
class Component:
    name: str
    source: str                     # path inside the archive, e.g. resources/BearingFMU.fmu
    connectors: list = field(default_factory=list)   # (name, kind, unit) ; kind input | output
    parameters: list = field(default_factory=list)   # (name, value, unit) ; value str -> ssv:String, int -> ssv:Integer


def enumeration_value(fmu, variable: str, item: str) -> int:
    """Value of ``item`` of the Enumeration ``variable`` of an FMU (FMI 2.0 modelDescription.xml): the
    ssv:Integer that sets the choice; fmpy's simulate_ssp and libcosim set Enumerations through Integer."""
    from xml.etree import ElementTree as ET
    with zipfile.ZipFile(fmu) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    sv = root.find(f"ModelVariables/ScalarVariable[@name='{variable}']")
    if sv is None or sv.find("Enumeration") is None:
        raise ValueError(f"{variable} is not an Enumeration variable of {fmu}")
    st = root.find(f"TypeDefinitions/SimpleType[@name='{sv.find('Enumeration').get('declaredType')}']")
    items = {it.get("name"): int(it.get("value")) for it in st.find("Enumeration")}
    if item not in items:
        raise ValueError(f"{variable} = {item!r} is not an item; allowed: {', '.join(items)}")
    return items[item]


def _unit_attr(unit):
    return f" unit={quoteattr(unit)}" if unit and unit != "1" else ""


def _param_xml(name, value, unit, ind):
    if isinstance(value, bool):
        raise TypeError(f"{name}: Boolean bindings are avoided (fmpy 0.3.32 sets every bound Boolean to true)")
    if isinstance(value, str):
        v = f'<ssv:String value={quoteattr(value)}/>'
    elif isinstance(value, int):
        v = f'<ssv:Integer value="{value}"/>'
    else:
        v = f'<ssv:Real value="{float(value)!r}"{_unit_attr(unit)}/>'
    return f'{ind}<ssv:Parameter name={quoteattr(name)}>{v}</ssv:Parameter>'


def ssd_xml(name: str, description: str, components: list[Component], connections: list, start: float,
            stop: float, step: float, generator: str) -> str:
    """connections: (startElement, startConnector, endElement, endConnector)."""
    used = {u for c in components for _, _, u in c.connectors + c.parameters if u and u != "1"}
    L = ['<?xml version="1.0" encoding="UTF-8"?>',
         f'<ssd:SystemStructureDescription xmlns:ssd="{NS["ssd"]}" xmlns:ssc="{NS["ssc"]}" xmlns:ssv="{NS["ssv"]}"',
         f'    xmlns:osp="{NS["osp"]}" version="1.0" name={quoteattr(name)} generationTool={quoteattr(generator)}>',
         f'  <ssd:System name={quoteattr(name)} description={quoteattr(description)}>',
         '    <ssd:Elements>']
    for c in components:
        L.append(f'      <ssd:Component name={quoteattr(c.name)} source={quoteattr(c.source)} '
                 'type="application/x-fmu-sharedlibrary">')
        if c.connectors:
            L.append('        <ssd:Connectors>')
            for cn, kind, unit in c.connectors:
                L.append(f'          <ssd:Connector name={quoteattr(cn)} kind="{kind}"><ssc:Real{_unit_attr(unit)}/>'
                         '</ssd:Connector>')
            L.append('        </ssd:Connectors>')
        if c.parameters:
            L += ['        <ssd:ParameterBindings>', '          <ssd:ParameterBinding>',
                  '            <ssd:ParameterValues>',
                  f'              <ssv:ParameterSet version="1.0" name={quoteattr(c.name + "_parameters")}>',
                  '                <ssv:Parameters>']
            L += [_param_xml(n, v, u, " " * 18) for n, v, u in c.parameters]
            L += ['                </ssv:Parameters>', '              </ssv:ParameterSet>',
                  '            </ssd:ParameterValues>', '          </ssd:ParameterBinding>',
                  '        </ssd:ParameterBindings>']
        L.append('      </ssd:Component>')
    L.append('    </ssd:Elements>')
    L.append('    <ssd:Connections>')
    for a, ac, b, bc in connections:
        L.append(f'      <ssd:Connection startElement={quoteattr(a)} startConnector={quoteattr(ac)} '
                 f'endElement={quoteattr(b)} endConnector={quoteattr(bc)}/>')
    L.append('    </ssd:Connections>')
    L.append('  </ssd:System>')
    L.append('  <ssd:Units>')
    for u in sorted(used):
        exps = " ".join(f'{k}="{v}"' for k, v in UNITS[u].items())
        L.append(f'    <ssc:Unit name={quoteattr(u)}><ssc:BaseUnit {exps}/></ssc:Unit>')
    L.append('  </ssd:Units>')
    L += [f'  <ssd:DefaultExperiment startTime="{start!r}" stopTime="{stop!r}">',
          '    <ssd:Annotations>',
          '      <ssc:Annotation type="com.opensimulationplatform">',
          f'        <osp:Algorithm><osp:FixedStepAlgorithm baseStepSize="{step!r}" numWorkerThreads="1"/>'
          '</osp:Algorithm>',
          '      </ssc:Annotation>',
          '    </ssd:Annotations>',
          '  </ssd:DefaultExperiment>',
          '</ssd:SystemStructureDescription>']
    return "\n".join(L) + "\n"


def write_ssp(path, ssd: str, fmus: dict) -> Path:
    """fmus: {name inside resources/: path of the .fmu on disk}."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd", ssd)
        for arc, src in fmus.items():
            z.write(src, f"resources/{arc}")
    return path
