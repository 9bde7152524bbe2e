"""MkDocs hooks of the manual (mkdocs.yml `hooks:`): the parts of pages that are generated at build time.

* `<!-- fmu-variables: BearingFMU -->` and `<!-- fmu-variables: BearingMapFMU -->` become the variables table of
  that FMU, read from the model description of an FMU built for this purpose into a temporary folder
  (`build_fmu.build`, the thin build, about 2 s; `bearing_cosim.map_fmu.build_map_fmu` on `maps/7218B_oil.nc` for
  linux64, about 4 s) through the generator that writes the FMU's own documentation/index.html
  (`bearing_cosim.fmu_build.variables_table_markdown`).
* `<!-- api: bearing_core -->` becomes one mkdocstrings block per name of the public face (`bearing_core._API`),
  so the API reference lists exactly what `import bearing_core` offers.

The FMUs are built once per process (a `mkdocs serve` rebuild reuses them). A build that fails fails the site.
"""
from __future__ import annotations

import re
import sys
import tempfile
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

from mkdocs.exceptions import PluginError

ROOT = Path(__file__).resolve().parent
MAP_FILE = ROOT / "maps" / "7218B_oil.nc"
_MARK_FMU = re.compile(r"<!-- fmu-variables: (\w+) -->")
_MARK_API = "<!-- api: bearing_core -->"
_models: dict = {}

# the public face by concern, in the order of bearing_core/__init__.py (module prefix of _API -> heading)
_API_GROUPS = (("bearing.", "Bearing definition"), ("lubrication.", "Lubricants"), ("models.", "Models"),
               ("heat.", "Heat"), ("session.", "Co-simulation session"), ("maps.", "Operating maps"),
               ("errors", "Errors"))


def _build_fmus() -> dict:
    """{model identifier: (model description element, how it was built)} of BearingFMU and BearingMapFMU."""
    if _models:
        return _models
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    from bearing_cosim.fmu_build import build
    from bearing_cosim.map_fmu import build_map_fmu
    with tempfile.TemporaryDirectory(prefix="bearing_docs_fmus_") as td:
        try:
            fmus = {"BearingFMU": (build(td), "`build_fmu.build` (the thin build of `bearing build-fmu`)"),
                    "BearingMapFMU": (build_map_fmu(MAP_FILE, td, ["linux64"]),
                                      f"`bearing build-map-fmu maps/{MAP_FILE.name} --platforms linux64`")}
        except Exception as e:   # noqa: BLE001 - any build failure fails the site, with its reason
            raise PluginError(f"building the FMUs for the variables tables failed: {type(e).__name__}: {e}") from e
        for mid, (fmu, how) in fmus.items():
            with zipfile.ZipFile(fmu) as z:
                _models[mid] = (ET.fromstring(z.read("modelDescription.xml")), how)
    return _models


def fmu_variables_markdown(model_id: str) -> str:
    """The variables table of one FMU as Markdown, with a line saying where it comes from."""
    from bearing_cosim.fmu_build import variables_table_markdown
    models = _build_fmus()
    if model_id not in models:
        raise PluginError(f"<!-- fmu-variables: {model_id} -->: no such FMU; allowed: {', '.join(sorted(models))}")
    xml, how = models[model_id]
    n = len(xml.find("ModelVariables"))
    return (f"*Generated when this site was built, from the model description of {model_id} "
            f"{xml.get('version')} (GUID `{xml.get('guid')}`, {n} variables) built by {how}.*\n\n"
            + variables_table_markdown(xml))


def api_markdown() -> str:
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    from bearing_core import _API
    out = []
    for prefix, title in _API_GROUPS:
        names = [n for n, mod in _API.items() if mod.startswith(prefix)]
        if names:
            out.append(f"## {title}\n")
            out += [f"::: bearing_core.{_API[n]}.{n}\n" for n in names]
    missing = sorted(set(_API) - {n for p, _ in _API_GROUPS for n, m in _API.items() if m.startswith(p)})
    if missing:
        raise PluginError(f"public names of bearing_core without a group in mkdocs_hooks._API_GROUPS: {missing}")
    return "\n".join(out)


_SSP_README = '--8<-- "ssp_examples/README.md"'


def on_page_markdown(markdown: str, page, config, files):
    if _SSP_README in markdown:
        # the SSP examples' README, included with its links into docs/ made relative to the manual's pages
        text = (ROOT / "ssp_examples" / "README.md").read_text(encoding="utf-8")
        markdown = markdown.replace(_SSP_README, text.replace("](../docs/", "](../"))
    if "<!-- fmu-variables:" in markdown:
        markdown = _MARK_FMU.sub(lambda m: fmu_variables_markdown(m.group(1)), markdown)
    if _MARK_API in markdown:
        markdown = markdown.replace(_MARK_API, api_markdown())
    return markdown
