"""modelDescription.xml: fmpy's validation, the FMI 2.0 schema, the interface of docs/model.md §5."""

import os
import zipfile

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

PARAMETERS = [
    "shape", "B", "L", "t", "Ro", "Ri", "massModel", "H", "rho", "W", "hG", "Ic",
    "interface", "kn", "fm", "formulation", "restitution", "eta", "g", "maxSteps",
]
OUTPUTS = [
    "theta", "omega", "thetaOverAlpha", "af", "contactLength", "MR", "regime",
    "impacts", "zeroCrossings", "overturned", "Fx", "Fz",
]
CALCULATED = ["mass", "weight", "R0", "alpha", "IO", "etaHousner", "thetaJo", "thetaC", "thetaOv"]


def variables(md):
    return {v.name: v for v in md.modelVariables}


def test_fmpy_validation_reports_no_problem(fmu_path):
    assert validate_fmu(fmu_path) == []


def test_xml_validates_against_the_fmi2_schema(fmu_path):
    from lxml import etree
    import fmpy

    schema_dir = os.path.join(os.path.dirname(fmpy.__file__), "schema", "fmi2")
    schema = etree.XMLSchema(etree.parse(os.path.join(schema_dir, "fmi2ModelDescription.xsd")))
    with zipfile.ZipFile(fmu_path) as z:
        doc = etree.fromstring(z.read("modelDescription.xml"))
    schema.assertValid(doc)


def test_archive_layout_is_reproducible(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        infos = z.infolist()
    names = [i.filename for i in infos]
    assert names == sorted(names)
    # win64 where the machine has the Windows toolchain (test_platforms.py says when not)
    assert [n for n in names if n != "binaries/win64/RockingBlock.dll"] == [
        "binaries/linux64/RockingBlock.so",
        "documentation/index.html",
        "documentation/licenses/license.txt",  # the crates linked in (xtask/src/licences.rs)
        "modelDescription.xml",
    ]
    assert all(i.date_time == (1980, 1, 1, 0, 0, 0) for i in infos)



def test_a_win64_binary_ships_the_notices_of_its_c_runtime(fmu_path):
    """mingw-w64's gcc links its startup code (ZPL-2.1, whose clause 2 asks
    a binary redistribution to reproduce the notice) and libgcc statically
    into the DLL, which imports only Windows' own libraries; the licence file
    carries the copyright files of the Debian packages that hold them."""
    import shutil
    import subprocess

    with zipfile.ZipFile(fmu_path) as z:
        if "binaries/win64/RockingBlock.dll" not in z.namelist():
            pytest.skip("no win64 binary (test_platforms.py says why)")
        dll = z.read("binaries/win64/RockingBlock.dll")
        text = z.read("documentation/licenses/license.txt").decode()
    # no mingw runtime DLL is imported: its code is in the binary
    assert b"libwinpthread" not in dll and b"libgcc_s" not in dll
    assert b"Mingw-w64 runtime failure" in dll
    section = text[text.index("The C runtime of the win64 binaries"):]
    assert "Redistributions in binary form must reproduce the accompanying" in section
    assert "GCC RUNTIME LIBRARY EXCEPTION" in section
    if shutil.which("dpkg-query") and shutil.which("x86_64-w64-mingw32-gcc"):
        libgcc = subprocess.run(
            ["x86_64-w64-mingw32-gcc", "-print-libgcc-file-name"],
            capture_output=True, text=True, check=True,
        ).stdout.strip()
        owner = subprocess.run(
            ["dpkg-query", "--search", os.path.realpath(libgcc)],
            capture_output=True, text=True, check=True,
        ).stdout.split(":")[0]
        assert f"== {owner} " in section

def test_co_simulation_capabilities(model_description):
    cs = model_description.coSimulation
    assert model_description.fmiVersion == "2.0"
    # Model Exchange beside it: test_model_exchange.py
    assert model_description.modelExchange.modelIdentifier == "RockingBlock"
    assert cs.modelIdentifier == "RockingBlock"
    assert cs.canHandleVariableCommunicationStepSize
    assert cs.canInterpolateInputs
    assert cs.maxOutputDerivativeOrder == 2
    assert cs.canGetAndSetFMUstate
    assert cs.canSerializeFMUstate
    assert not cs.canBeInstantiatedOnlyOncePerProcess
    assert not cs.needsExecutionTool
    assert not cs.canRunAsynchronuously
    assert not cs.providesDirectionalDerivative


def test_raw_capability_flags_are_only_the_true_ones(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        xml = z.read("modelDescription.xml").decode()
    cs = xml[xml.index("<CoSimulation"):]
    cs = cs[: cs.index(">")]
    assert 'needsExecutionTool="false"' in cs
    assert 'canBeInstantiatedOnlyOncePerProcess="false"' in cs
    # every other flag that is present is true
    import re

    for name, value in re.findall(r'(\w+)="([^"]*)"', cs):
        if name in ("modelIdentifier", "needsExecutionTool", "canBeInstantiatedOnlyOncePerProcess"):
            continue
        assert value in ("true", "2"), (name, value)


def test_every_public_variable_is_declared(model_description):
    v = variables(model_description)
    for n in PARAMETERS:
        assert v[n].causality == "parameter" and v[n].variability == "fixed", n
    assert v["ag"].causality == "input" and v["ag"].variability == "continuous"
    for n in OUTPUTS:
        assert v[n].causality == "output", n
    for n in ("theta", "omega"):
        assert v[n].initial == "exact" and v[n].variability == "continuous"
    for n in ("regime", "impacts", "zeroCrossings"):
        assert v[n].type == "Integer" and v[n].variability == "discrete"
    assert v["overturned"].type == "Boolean" and v["overturned"].variability == "discrete"
    for n in CALCULATED:
        assert v[n].causality == "calculatedParameter", n
    assert all(x.description for x in model_description.modelVariables)


def test_enumerations(model_description):
    v = variables(model_description)
    items = lambda n: [i.name for i in v[n].declaredType.items]  # noqa: E731
    assert items("shape") == ["solidRectangle", "hollowRectangle", "solidCircle", "hollowCircle"]
    assert items("massModel") == ["prism", "lumped"]
    assert items("interface") == ["rigid", "elastic", "elastoPlastic"]
    assert items("formulation") == ["costa", "shiftingPivot"]
    assert items("restitution") == ["housner", "given"]
    assert all(v[n].type == "Enumeration" for n in ("shape", "massModel", "interface", "formulation", "restitution"))


@pytest.mark.parametrize(
    "name, unit, display",
    [
        ("theta", "rad", "deg"),
        ("alpha", "rad", "deg"),
        ("thetaOv", "rad", "deg"),
        ("kn", "Pa/m", "MPa/m"),
        ("fm", "Pa", "MPa"),
        ("Fx", "N", "kN"),
        ("Fz", "N", "kN"),
        ("W", "N", "kN"),
        ("ag", "m/s2", "g"),
    ],
)
def test_units_and_display_units(model_description, name, unit, display):
    v = variables(model_description)[name]
    assert v.unit == unit
    assert v.displayUnit == display
    units = {u.name: u for u in model_description.unitDefinitions}
    du = {d.name: d for d in units[unit].displayUnits}
    assert display in du
    if display == "deg":
        assert du[display].factor == pytest.approx(57.29577951308232, rel=1e-15)
    if display == "g":
        assert du[display].factor == pytest.approx(1 / 9.80665, rel=1e-15)


def test_model_structure_dependencies(model_description):
    md = model_description
    index = {v.name: i for i, v in enumerate(md.modelVariables)}
    outputs = {u.variable.name: {d.name for d in u.dependencies} for u in md.outputs}
    assert set(outputs) == {v.name for v in md.modelVariables if v.causality == "output"}
    # direct feedthrough of ag only where the equation of motion enters, of av (the apparent
    # weight N = m (g + av), docs/model.md §6) also where the contact at N does
    assert (outputs["Fx"] == outputs["Fz"] == outputs["angularAcceleration"] == outputs["frictionDemand"]
            == {"ag", "av"})
    # omega and omegaW are one another referred by sqrt(I(phi, N)/I(phi, W)): whichever
    # is not the integrated state depends on av directly (docs/model-exchange.md)
    for n in ("af", "contactLength", "MR", "regime", "apparentWeight", "omega", "omegaW"):
        assert outputs[n] == {"av"}, n
    for n in ("theta", "impacts", "zeroCrossings", "overturned"):
        assert outputs[n] == set(), n
    initial = {u.variable.name: {d.name for d in u.dependencies} for u in md.initialUnknowns}
    assert set(CALCULATED) <= set(initial)
    assert "theta" not in initial and "omega" not in initial
    assert initial["alpha"] == {"shape", "B", "Ro", "massModel", "H", "hG"}
    assert "fm" in initial["thetaC"] and "hG" not in initial["thetaC"]
    assert "theta" in initial["af"]
    assert initial["impacts"] == initial["zeroCrossings"] == set()
    assert "ag" in initial["angularAcceleration"]
    order = [index[u.variable.name] for u in md.initialUnknowns]
    assert order == sorted(order)


def test_default_experiment(model_description):
    de = model_description.defaultExperiment
    assert de.startTime == "0" or float(de.startTime) == 0.0
    assert float(de.tolerance) > 0
    assert float(de.stepSize) > 0


def test_guid_is_content_derived_and_embedded(fmu_path, model_description):
    guid = model_description.guid
    assert guid.startswith("{") and guid.endswith("}") and len(guid) == 38
    with zipfile.ZipFile(fmu_path) as z:
        so = z.read("binaries/linux64/RockingBlock.so")
        html = z.read("documentation/index.html").decode()
    assert guid.encode() in so
    assert guid in html


def test_documentation_lists_every_variable(fmu_path, model_description):
    with zipfile.ZipFile(fmu_path) as z:
        html = z.read("documentation/index.html").decode()
    for v in model_description.modelVariables:
        assert f'<tr id="{v.name}">' in html, v.name


def test_documentation_names_the_interfaces_and_platforms_the_archive_has(fmu_path, model_description):
    with zipfile.ZipFile(fmu_path) as z:
        html = z.read("documentation/index.html").decode()
        platforms = sorted({n.split("/")[1] for n in z.namelist() if n.startswith("binaries/")})
    using = html[html.index("<h2>Using the FMU</h2>"):][:600]
    assert ("Co-Simulation" in using) == (model_description.coSimulation is not None)
    assert ("Model Exchange" in using) == (model_description.modelExchange is not None)
    assert "only" not in using.split("</li>")[0]
    for platform in platforms:
        assert platform in using, platform


def test_read_with_schema_validation(fmu_path):
    md = read_model_description(fmu_path, validate=True, validate_variable_names=True, validate_model_structure=True)
    assert md.modelName == "RockingBlock"
