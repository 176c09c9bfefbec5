"""The frame + block system described once as an SSP file, and a container FMU from it.

`write_ssp` writes an SSP 1.0 archive (a zip): `SystemStructure.ssd` with the
two components (ShearFrame.fmu, RockingBlock.fmu under resources/), the
system's input `ag` and outputs `theta`, `aFloor`, the connections

    frame.a[i]        -> block.ag
    block.FxSupport   -> frame.Fx[i]
    block.FzSupport   -> frame.Fz[i]

(the force of the body on its support: no sign change, so a host that copies
values as they are couples them right) and every parameter value as an
inline ParameterSet (ssv) in each component's ParameterBindings. With
`forces="negated"` it connects `block.Fx`, `block.Fz` with a
LinearTransformation of factor -1 instead, the standard's way of saying "the
opposite" (the form for a block FMU without the support outputs). The system
carries OMSimulator's vendor annotation (its master and step), which
OMSimulator needs to import the file and other readers skip.

`container_from_ssp` reads that description with fmpy's SSD parser (an
independent reader of the standard) and hands components, connections and
parameter values to fmu-manipulation-toolbox's `AssemblyNode`, which writes
the container FMU. The toolbox's runtime copies a connection's value as it
is: it has no gain, so a connection with a factor other than 1 cannot be
represented. `signs="refuse"` (the default) raises then; `signs="drop"`
builds the container with the factors left out and returns the dropped
connections. The toolbox's own `.ssp` reader (`Assembly("x.ssp")`) ignores
ParameterBindings and LinearTransformations alike; this module passes the
parameters as the container's start values.
"""

import io
import zipfile
from pathlib import Path
from xml.sax.saxutils import quoteattr

SSD_NS = "http://ssp-standard.org/SSP1/SystemStructureDescription"
SSC_NS = "http://ssp-standard.org/SSP1/SystemStructureCommon"
SSV_NS = "http://ssp-standard.org/SSP1/SystemStructureParameterValues"
#: OMSimulator's vendor annotation: its type, and the namespace OMSimulator writes for its elements
#: (an identifier: OMSimulator matches the prefix "oms:", nothing fetches the address).
OMS_ANNOTATION = "org.openmodelica"
OMS_NS = "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd"
#: The relative tolerance OMSimulator reads from the annotation: it passes it to every FMU's
#: fmi2SetupExperiment as defined (0 when absent, which ShearFrame refuses), and it is the tolerance
#: of its solver of the algebraic loop frame.a -> block.ag -> block.FxSupport -> frame.Fx. 1e-9 is
#: the FMUs' own default (their DefaultExperiment), so they integrate as in any other host.
OMS_TOLERANCE = 1e-9


def _value(name, value):
    if isinstance(value, bool):
        return f'<ssv:Parameter name={quoteattr(name)}><ssv:Boolean value="{str(value).lower()}"/></ssv:Parameter>'
    if isinstance(value, int):
        return f'<ssv:Parameter name={quoteattr(name)}><ssv:Integer value="{value}"/></ssv:Parameter>'
    return f'<ssv:Parameter name={quoteattr(name)}><ssv:Real value="{float(value)!r}"/></ssv:Parameter>'


def _component(name, source, connectors, parameters):
    rows = [f'    <ssd:Component name="{name}" source="{source}" type="application/x-fmu-sharedlibrary">',
            "      <ssd:Connectors>"]
    for cname, kind in connectors:
        rows.append(f'        <ssd:Connector name={quoteattr(cname)} kind="{kind}"><ssc:Real/></ssd:Connector>')
    rows.append("      </ssd:Connectors>")
    if parameters:
        rows += ["      <ssd:ParameterBindings>", "        <ssd:ParameterBinding>",
                 "          <ssd:ParameterValues>",
                 f'            <ssv:ParameterSet version="1.0" name="{name}">', "              <ssv:Parameters>"]
        rows += [f"                {_value(k, v)}" for k, v in parameters.items()]
        rows += ["              </ssv:Parameters>", "            </ssv:ParameterSet>",
                 "          </ssd:ParameterValues>", "        </ssd:ParameterBinding>",
                 "      </ssd:ParameterBindings>"]
    rows.append("    </ssd:Component>")
    return rows


def _connection(start, sconn, end, econn, factor=None):
    s = f' startElement="{start}"' if start else ""
    e = f' endElement="{end}"' if end else ""
    head = f"    <ssd:Connection{s} startConnector={quoteattr(sconn)}{e} endConnector={quoteattr(econn)}"
    if factor is None:
        return [head + "/>"]
    return [head + ">", f'      <ssc:LinearTransformation factor="{factor!r}" offset="0.0"/>',
            "    </ssd:Connection>"]


def _openmodelica_annotation(step):
    """The system's vendor annotation OMSimulator needs to import the file.

    OMSimulator's SSD import takes the kind of a system (weakly coupled
    co-simulation, or strongly coupled Model Exchange) and its master from
    this annotation only; without it the import stops with "Unable to add
    System". The master "oms-ma" is its fixed-step one, at the step `step`
    (s; without it OMSimulator does not advance), with the tolerance
    OMS_TOLERANCE. Other readers skip the annotation (the standard's
    Annotation holds any element); docs/cosimulation-hosts.md §6.
    """
    return ['    <ssd:Annotations>',
            f'      <ssc:Annotation type="{OMS_ANNOTATION}">',
            f'        <oms:Annotations xmlns:oms="{OMS_NS}">',
            "          <oms:SimulationInformation>",
            f'            <oms:FixedStepMaster description="oms-ma" stepSize="{step!r}" '
            f'relativeTolerance="{OMS_TOLERANCE!r}"/>',
            "          </oms:SimulationInformation>",
            "        </oms:Annotations>",
            "      </ssc:Annotation>",
            "    </ssd:Annotations>"]


def system_structure(frame_parameters, block_parameters, floor, step, forces="support"):
    """The text of SystemStructure.ssd for a block on floor `floor` of the frame.

    forces: "support" connects the block's FxSupport, FzSupport to the
    frame's Fx[floor], Fz[floor] as they are; "negated" connects its Fx, Fz
    through LinearTransformations of factor -1.
    """
    if forces not in ("support", "negated"):
        raise ValueError(f"forces = {forces!r}: 'support' or 'negated'")
    a, fx, fz = f"a[{floor}]", f"Fx[{floor}]", f"Fz[{floor}]"
    out_x, out_z, factor = ("FxSupport", "FzSupport", None) if forces == "support" else ("Fx", "Fz", -1.0)
    rows = ['<?xml version="1.0" encoding="UTF-8"?>',
            f'<ssd:SystemStructureDescription xmlns:ssd="{SSD_NS}" xmlns:ssc="{SSC_NS}" xmlns:ssv="{SSV_NS}"'
            ' version="1.0" name="BlockOnFrame">',
            '  <ssd:System name="BlockOnFrame" description="A rocking block on a floor of a shear frame">',
            "  <ssd:Connectors>",
            '    <ssd:Connector name="ag" kind="input"><ssc:Real/></ssd:Connector>',
            '    <ssd:Connector name="theta" kind="output"><ssc:Real/></ssd:Connector>',
            '    <ssd:Connector name="aFloor" kind="output"><ssc:Real/></ssd:Connector>',
            "  </ssd:Connectors>",
            "  <ssd:Elements>"]
    rows += _component("frame", "resources/ShearFrame.fmu",
                       [("ag", "input"), (fx, "input"), (fz, "input"), (a, "output")], frame_parameters)
    rows += _component("block", "resources/RockingBlock.fmu",
                       [("ag", "input"), ("theta", "output"), (out_x, "output"), (out_z, "output")],
                       block_parameters)
    rows += ["  </ssd:Elements>", "  <ssd:Connections>"]
    rows += _connection(None, "ag", "frame", "ag")
    rows += _connection("frame", a, "block", "ag")
    rows += _connection("block", out_x, "frame", fx, factor)
    rows += _connection("block", out_z, "frame", fz, factor)
    rows += _connection("block", "theta", None, "theta")
    rows += _connection("frame", a, None, "aFloor")
    rows += ["  </ssd:Connections>"]
    rows += _openmodelica_annotation(step)
    rows += ["  </ssd:System>",
             "  <ssd:DefaultExperiment startTime=\"0.0\">",
             f'    <ssd:Annotations><ssc:Annotation type="org.rocking.step"><Step value="{step!r}"/></ssc:Annotation>'
             "</ssd:Annotations>",
             "  </ssd:DefaultExperiment>",
             "</ssd:SystemStructureDescription>", ""]
    return "\n".join(rows)


def write_ssp(path, frame_fmu, block_fmu, frame_parameters, block_parameters, floor, step, forces="support"):
    """Write the SSP archive at `path` (the FMUs copied into its resources/); `forces` as in system_structure."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd",
                   system_structure(frame_parameters, block_parameters, floor, step, forces))
        z.write(frame_fmu, "resources/ShearFrame.fmu")
        z.write(block_fmu, "resources/RockingBlock.fmu")
    return Path(path)


def fmpy_parameter_set(path):
    """The archive's ParameterBindings as the `parameter_set` of fmpy's simulate_ssp
    (which does not read them itself): one fmpy ParameterSet, names "component.variable"."""
    from fmpy.ssp.ssd import Parameter, ParameterSet

    _, _, parameters = read_ssp(path)
    pset = ParameterSet(name="bindings")
    for component, values in parameters.items():
        for name, value in values.items():
            kind = "Integer" if isinstance(value, int) and not isinstance(value, bool) else "Real"
            pset.parameters.append(Parameter(name=f"{component}.{name}", type=kind, value=value))
    return pset


def read_ssp(path):
    """(components, connections, parameters) of an SSP archive.

    components: {name: source}; connections: [(start element or None, start
    connector, end element or None, end connector, factor)]; parameters:
    {component: {name: value}} from the inline ParameterSets. fmpy's SSD
    parser (which validates the file against the standard's schema) reads
    components and parameters; it drops a connection's LinearTransformation,
    so connections are read here with ElementTree.
    """
    import xml.etree.ElementTree as ET

    from fmpy.ssp.ssd import read_ssd

    ssd = read_ssd(str(path))
    components = {e.name: e.source for e in ssd.system.elements}
    parameters = {}
    for e in ssd.system.elements:
        values = parameters.setdefault(e.name, {})
        for binding in e.parameterBindings:
            for pset in binding.parameterValues:
                for p in pset.parameters:
                    values[p.name] = _typed(p.type, p.value)
    ns = {"ssd": SSD_NS, "ssc": SSC_NS}
    root = ET.fromstring(ssd_text(path))
    connections = []
    for c in root.findall("ssd:System/ssd:Connections/ssd:Connection", ns):
        t = c.find("ssc:LinearTransformation", ns)
        factor = float(t.get("factor", "1")) if t is not None else 1.0
        connections.append((c.get("startElement"), c.get("startConnector"), c.get("endElement"),
                            c.get("endConnector"), factor))
    return components, connections, parameters


def _typed(kind, text):
    if kind == "Real":
        return float(text)
    if kind == "Integer":
        return int(text)
    if kind == "Boolean":
        return text == "true"
    return text


def container_from_ssp(ssp, out_dir, step, signs="refuse", name="BlockOnFrame", sequential=False):
    """Build the container FMU `out_dir/name.fmu` from the SSP archive; returns (path, dropped)."""
    from fmu_manipulation_toolbox.assembly import AssemblyNode

    out_dir = Path(out_dir)
    components, connections, parameters = read_ssp(ssp)
    with zipfile.ZipFile(ssp) as z:
        for source in components.values():
            (out_dir / Path(source).name).write_bytes(z.read(source))
    files = {c: Path(s).name for c, s in components.items()}
    node = AssemblyNode(f"{name}.fmu", step_size=step, auto_link=False, auto_input=False, auto_output=False,
                        sequential=sequential)
    for component in components:
        node.add_fmu(files[component])
    if signs not in ("refuse", "drop"):
        raise ValueError(f"signs = {signs!r}: 'refuse' or 'drop'")
    dropped = []
    for start, sconn, end, econn, factor in connections:
        if factor != 1.0:
            if signs == "refuse":
                raise ValueError(f"{ssp}: the connection {start}.{sconn} -> {end}.{econn} has the factor "
                                 f"{factor}; the container runtime copies values as they are")
            dropped.append((start, sconn, end, econn, factor))
        if start and end:
            node.add_link(files[start], sconn, files[end], econn)
        elif end:
            node.add_input(sconn, files[end], econn)
        else:
            node.add_output(files[start], sconn, econn)
    for component, values in parameters.items():
        for key, value in values.items():
            node.add_start_value(files[component], key, _start_text(value))
    node.make_fmu(out_dir)
    return out_dir / f"{name}.fmu", dropped


def _start_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value)


def ssd_text(path):
    """SystemStructure.ssd of an archive, as text."""
    with zipfile.ZipFile(path) as z:
        return io.TextIOWrapper(z.open("SystemStructure.ssd"), encoding="utf-8").read()
