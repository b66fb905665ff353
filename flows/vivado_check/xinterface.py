"""The Vivado interface attributes of a VHDL top level, parsed and checked.

Vivado's IP packager groups the ports of a top level into bus interfaces from
their `X_INTERFACE_INFO` attributes ("VLNV INTERFACE_NAME LOGICAL_NAME") and
takes each interface's parameters from one `X_INTERFACE_PARAMETER` attribute
("XIL_INTERFACENAME name, KEY VALUE, ..."), UG994 "List of Supported X_
Attributes" and UG1118 "Inferring Bus Interfaces". A wrong attribute does not
stop the packager: it infers something else, or keeps a parameter that
contradicts the ports, and the block design fails later (or silently narrows a
bus). `problems()` lists what would go wrong, from the VHDL text alone:

- every port belongs to exactly one interface, with a bus definition and a
  logical name that exist (the logical ports of the AMD bus definitions
  axis_rtl, aximm_rtl (AXI4-Lite subset), clock_rtl, reset_rtl and
  interrupt_rtl, as listed in UG1037 "AXI4-Stream Signals" / "AXI4-Lite
  Signals" and UG994), each logical name once per interface;
- each port's direction fits its role (a slave's TVALID is an input ...);
- the parameters agree with the ports: TDATA_NUM_BYTES, TUSER_WIDTH, TID_WIDTH,
  TDEST_WIDTH, HAS_TLAST, HAS_TREADY, HAS_TKEEP, HAS_TSTRB (AXI4-Stream);
  PROTOCOL, DATA_WIDTH, ADDR_WIDTH, HAS_WSTRB, HAS_PROT, HAS_BRESP, HAS_RRESP,
  HAS_BURST/LOCK/CACHE/QOS/REGION (AXI4-Lite);
- the clock's ASSOCIATED_BUSIF names every bus interface exactly once and its
  ASSOCIATED_RESET names the reset; the reset says POLARITY ACTIVE_LOW.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

# Logical ports of each interface type, with the direction a *slave* (or, for
# signal interfaces, the IP) gives them: "in" or "out". A master reverses
# them. Sources: UG1037 (AXI Reference Guide) "AXI4-Stream Signals" and
# "AXI4-Lite Signals"; UG994 "List of Supported X_ Attributes" (clock CLK,
# reset RST, interrupt INTERRUPT).
LOGICAL_PORTS: dict[str, dict[str, str]] = {
    "xilinx.com:interface:axis:1.0": {
        "TDATA": "in", "TKEEP": "in", "TSTRB": "in", "TLAST": "in", "TUSER": "in",
        "TID": "in", "TDEST": "in", "TVALID": "in", "TREADY": "out",
    },
    "xilinx.com:interface:aximm:1.0": {
        "AWADDR": "in", "AWPROT": "in", "AWVALID": "in", "AWREADY": "out",
        "WDATA": "in", "WSTRB": "in", "WVALID": "in", "WREADY": "out",
        "BRESP": "out", "BVALID": "out", "BREADY": "in",
        "ARADDR": "in", "ARPROT": "in", "ARVALID": "in", "ARREADY": "out",
        "RDATA": "out", "RRESP": "out", "RVALID": "out", "RREADY": "in",
    },
    "xilinx.com:signal:clock:1.0": {"CLK": "in"},
    "xilinx.com:signal:reset:1.0": {"RST": "in"},
    "xilinx.com:signal:interrupt:1.0": {"INTERRUPT": "out"},
}  # fmt: skip
BUS_TYPES = ("xilinx.com:interface:axis:1.0", "xilinx.com:interface:aximm:1.0")
CLOCK, RESET, INTERRUPT = (
    "xilinx.com:signal:clock:1.0",
    "xilinx.com:signal:reset:1.0",
    "xilinx.com:signal:interrupt:1.0",
)
# AXI4-Lite: every signal but the optional WSTRB, AWPROT and ARPROT.
AXI4LITE_REQUIRED = {
    "AWADDR", "AWVALID", "AWREADY", "WDATA", "WVALID", "WREADY", "BRESP", "BVALID",
    "BREADY", "ARADDR", "ARVALID", "ARREADY", "RDATA", "RRESP", "RVALID", "RREADY",
}  # fmt: skip
AXIS_PARAMETERS = ("TDATA_NUM_BYTES", "TUSER_WIDTH", "HAS_TLAST", "HAS_TREADY")
AXIS_PARAMETERS += ("HAS_TKEEP", "HAS_TSTRB")
AXI4LITE_PARAMETERS = ("PROTOCOL", "DATA_WIDTH", "ADDR_WIDTH", "HAS_WSTRB", "HAS_PROT")


@dataclass
class Port:
    name: str
    direction: str  # in, out, inout
    width: int | None  # None: not a literal range


@dataclass
class Interface:
    name: str
    vlnv: str
    ports: dict[str, Port] = field(default_factory=dict)  # by logical name
    parameters: dict[str, str] = field(default_factory=dict)
    parameter_port: str | None = None  # the port X_INTERFACE_PARAMETER is on


@dataclass
class Top:
    entity: str
    generics: dict[str, str]  # name -> default value (as written)
    ports: dict[str, Port]
    info: dict[str, list[str]]  # port -> its X_INTERFACE_INFO strings
    parameter: dict[str, list[str]]  # port -> its X_INTERFACE_PARAMETER strings


def _strip_comments(text: str) -> str:
    return re.sub(r"--[^\n]*", "", text)


def _integer(expr: str, generics: dict[str, str]) -> int | None:
    """An integer expression of literals, generics (their values) and + - * /
    with parentheses, as port bounds use them; None for anything else."""
    text = re.sub(r"\b([A-Za-z]\w*)\b", lambda m: generics.get(m.group(1).upper(), "?"), expr)
    if not re.fullmatch(r"[\d\s+\-*/()]+", text):
        return None
    return int(eval(text.replace("/", "//"), {"__builtins__": {}}))  # noqa: S307 (digits only)


def _width(kind: str, generics: dict[str, str] | None = None) -> int | None:
    kind = kind.strip().lower()
    if kind == "std_logic" or kind == "std_ulogic":
        return 1
    m = re.fullmatch(r"std_u?logic_vector\s*\(\s*(.+?)\s+(downto|to)\s+(.+?)\s*\)", kind)
    if not m:
        return None
    upper = {k.upper(): v for k, v in (generics or {}).items()}
    high, low = _integer(m.group(1), upper), _integer(m.group(3), upper)
    if high is None or low is None:
        return None
    return abs(high - low) + 1


def _clause(text: str, keyword: str) -> str | None:
    """The parenthesised list after `keyword` (generic or port)."""
    m = re.search(rf"\b{keyword}\s*\(", text, re.IGNORECASE)
    if not m:
        return None
    depth, i = 1, m.end()
    while depth and i < len(text):
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        i += 1
    return text[m.end() : i - 1]


def _split_declarations(clause: str) -> list[str]:
    parts, depth, start = [], 0, 0
    for i, c in enumerate(clause):
        depth += {"(": 1, ")": -1}.get(c, 0)
        if c == ";" and depth == 0:
            parts.append(clause[start:i])
            start = i + 1
    parts.append(clause[start:])
    return [p.strip() for p in parts if p.strip()]


def parse(
    text: str, entity: str = "fastnms_axi", generics_override: dict[str, str] | None = None
) -> Top:
    """The entity `entity` of a VHDL file: generics, ports and the interface
    attributes of its declarative part. Port widths and `integer'image(G)` in
    the attributes are evaluated with the generics' defaults, or with the
    values in `generics` (as a build with those generics would have them)."""
    code = _strip_comments(text)
    m = re.search(
        rf"\bentity\s+{entity}\s+is\b(.*?)\bend\s+entity\s+{entity}\s*;",
        code,
        re.IGNORECASE | re.DOTALL,
    )
    if not m:
        raise ValueError(f"no 'entity {entity} is ... end entity {entity};'")
    body = m.group(1)
    generics: dict[str, str] = {}
    for decl in _split_declarations(_clause(body, "generic") or ""):
        names, _, rest = decl.partition(":")
        default = rest.partition(":=")[2].strip()
        for name in names.split(","):
            generics[name.strip()] = default.strip('"')
    values = {**generics, **{k: str(v) for k, v in (generics_override or {}).items()}}
    port_clause = _clause(body, "port") or ""
    ports: dict[str, Port] = {}
    for decl in _split_declarations(port_clause):
        mm = re.fullmatch(r"([\w\s,]+):\s*(in|out|inout|buffer)\s+(.*)", decl, re.DOTALL | re.I)
        if not mm:
            raise ValueError(f"cannot parse the port declaration '{decl}'")
        for name in mm.group(1).split(","):
            ports[name.strip().lower()] = Port(
                name.strip().lower(), mm.group(2).lower(), _width(mm.group(3), values)
            )
    after_ports = body[body.index(port_clause) + len(port_clause) :]
    info: dict[str, list[str]] = {}
    parameter: dict[str, list[str]] = {}
    piece = r"(?:\"[^\"]*\"|integer'image\s*\(\s*\w+\s*\))"
    pattern = re.compile(
        r"\battribute\s+(x_interface_info|x_interface_parameter)\s+of\s+(\w+)\s*:\s*signal\s+is"
        rf"\s+((?:{piece}\s*&?\s*)+);",
        re.IGNORECASE,
    )
    for kind, port, strings in pattern.findall(after_ports):
        value = ""
        for literal, name in re.findall(r"\"([^\"]*)\"|integer'image\s*\(\s*(\w+)\s*\)", strings):
            value += values.get(name, "?") if name else literal
        target = info if kind.lower() == "x_interface_info" else parameter
        target.setdefault(port.lower(), []).append(value)
    return Top(entity, generics, ports, info, parameter)


def interfaces(top: Top) -> tuple[dict[str, Interface], list[str]]:
    """The interfaces the attributes describe, and the problems met building them."""
    found: dict[str, Interface] = {}
    problems = []
    for port, values in top.info.items():
        if port not in top.ports:
            problems.append(f"X_INTERFACE_INFO on '{port}', which is not a port")
            continue
        triplets = [t.split() for v in values for t in v.split(",")]
        if len(triplets) != 1 or len(triplets[0]) != 3:
            problems.append(
                f"port {port}: belongs to {len(triplets)} interfaces, or its X_INTERFACE_INFO "
                f"is not 'VLNV NAME LOGICAL' ({values})"
            )
            continue
        vlnv, name, logical = triplets[0]
        busif = found.setdefault(name, Interface(name, vlnv))
        if busif.vlnv != vlnv:
            problems.append(f"interface {name}: two bus definitions, {busif.vlnv} and {vlnv}")
        if vlnv not in LOGICAL_PORTS:
            problems.append(f"port {port}: unknown bus definition {vlnv}")
        elif logical not in LOGICAL_PORTS[vlnv]:
            problems.append(
                f"port {port}: {logical} is not a logical port of {vlnv} "
                f"({' '.join(LOGICAL_PORTS[vlnv])})"
            )
        if logical in busif.ports:
            problems.append(
                f"interface {name}: {logical} on two ports, {busif.ports[logical].name} and {port}"
            )
        busif.ports[logical] = top.ports[port]
    for port in top.ports:
        if port not in top.info:
            problems.append(f"port {port}: no X_INTERFACE_INFO (belongs to no interface)")
    for port, values in top.parameter.items():
        if port not in top.ports:
            problems.append(f"X_INTERFACE_PARAMETER on '{port}', which is not a port")
            continue
        if len(values) != 1:
            problems.append(f"port {port}: {len(values)} X_INTERFACE_PARAMETER attributes")
        items = [item.strip() for item in values[0].split(",") if item.strip()]
        pairs = {}
        for item in items:
            key, _, value = item.partition(" ")
            if key in pairs:
                problems.append(f"port {port}: parameter {key} given twice")
            pairs[key] = value.strip()
        name = pairs.pop("XIL_INTERFACENAME", None)
        if name is None:
            problems.append(f"port {port}: X_INTERFACE_PARAMETER without XIL_INTERFACENAME")
            continue
        busif = found.get(name)
        if busif is None:
            problems.append(f"port {port}: X_INTERFACE_PARAMETER names no interface '{name}'")
            continue
        if port not in {p.name for p in busif.ports.values()}:
            problems.append(f"port {port}: parameters of {name}, a port of another interface")
        if busif.parameter_port is not None:
            problems.append(
                f"interface {name}: parameters on two ports, {busif.parameter_port} and {port}"
            )
        busif.parameter_port = port
        busif.parameters = pairs
    return found, problems


def _int(busif: Interface, key: str, problems: list[str]) -> int | None:
    value = busif.parameters.get(key)
    if value is None:
        problems.append(f"interface {busif.name}: no {key} parameter")
        return None
    if not re.fullmatch(r"\d+", value):
        problems.append(f"interface {busif.name}: {key} {value} is not a number")
        return None
    return int(value)


def _flag(busif: Interface, key: str, present: bool, problems: list[str]) -> None:
    value = _int(busif, key, problems)
    if value is not None and value != int(present):
        problems.append(
            f"interface {busif.name}: {key} {value} but the port is "
            f"{'present' if present else 'absent'}"
        )


def _width_of(busif: Interface, logical: str, problems: list[str]) -> int:
    """The width of a logical port (0 when absent)."""
    port = busif.ports.get(logical)
    if port is None:
        return 0
    if port.width is None:
        problems.append(f"port {port.name}: width not a literal range, cannot be checked")
        return 0
    return port.width


def _check_axis(busif: Interface, problems: list[str]) -> None:
    for key in AXIS_PARAMETERS:
        if key not in busif.parameters:
            problems.append(f"interface {busif.name}: no {key} parameter")
    if "TDATA" not in busif.ports or "TVALID" not in busif.ports:
        problems.append(f"interface {busif.name}: AXI4-Stream without TDATA or TVALID")
    tdata = _width_of(busif, "TDATA", problems)
    if tdata % 8:
        problems.append(f"interface {busif.name}: TDATA is {tdata} bits, not whole bytes")
    nbytes = busif.parameters.get("TDATA_NUM_BYTES")
    if nbytes is not None and nbytes != str(tdata // 8):
        problems.append(
            f"interface {busif.name}: TDATA_NUM_BYTES {nbytes} but TDATA is {tdata} bits"
        )
    for logical, key in (("TUSER", "TUSER_WIDTH"), ("TID", "TID_WIDTH"), ("TDEST", "TDEST_WIDTH")):
        width = _width_of(busif, logical, problems)
        value = busif.parameters.get(key)
        if (value is not None or width) and value != str(width):
            problems.append(f"interface {busif.name}: {key} {value} but {logical} is {width} bits")
    for logical in ("TLAST", "TREADY", "TKEEP", "TSTRB"):
        if f"HAS_{logical}" in busif.parameters:
            _flag(busif, f"HAS_{logical}", logical in busif.ports, problems)
    for logical in ("TKEEP", "TSTRB"):
        width = _width_of(busif, logical, problems)
        if width and width * 8 != tdata:
            problems.append(
                f"interface {busif.name}: {logical} is {width} bits for {tdata} bits of TDATA"
            )


def _check_aximm(busif: Interface, problems: list[str]) -> None:
    for key in AXI4LITE_PARAMETERS:
        if key not in busif.parameters:
            problems.append(f"interface {busif.name}: no {key} parameter")
    protocol = busif.parameters.get("PROTOCOL")
    if protocol is not None and protocol != "AXI4LITE":
        problems.append(f"interface {busif.name}: PROTOCOL {protocol}, only AXI4LITE is checked")
    missing = AXI4LITE_REQUIRED - set(busif.ports)
    if missing:
        problems.append(f"interface {busif.name}: AXI4-Lite without {' '.join(sorted(missing))}")
    for key, logicals in (("DATA_WIDTH", ("WDATA", "RDATA")), ("ADDR_WIDTH", ("AWADDR", "ARADDR"))):
        value = busif.parameters.get(key)
        for logical in logicals:
            width = _width_of(busif, logical, problems)
            if logical in busif.ports and value is not None and value != str(width):
                problems.append(f"interface {busif.name}: {key} {value} but {logical} is {width}")
    data = _width_of(busif, "WDATA", problems)
    wstrb = _width_of(busif, "WSTRB", problems)
    if wstrb and wstrb * 8 != data:
        problems.append(f"interface {busif.name}: WSTRB is {wstrb} bits for {data} of WDATA")
    if "HAS_WSTRB" in busif.parameters:
        _flag(busif, "HAS_WSTRB", "WSTRB" in busif.ports, problems)
    prot = {"AWPROT", "ARPROT"} & set(busif.ports)
    if len(prot) == 1:
        problems.append(f"interface {busif.name}: {prot.pop()} without the other *PROT")
    if "HAS_PROT" in busif.parameters:
        _flag(busif, "HAS_PROT", bool(prot), problems)
    for logical in ("BRESP", "RRESP"):
        if f"HAS_{logical}" in busif.parameters:
            _flag(busif, f"HAS_{logical}", logical in busif.ports, problems)
    for key in ("HAS_BURST", "HAS_LOCK", "HAS_CACHE", "HAS_QOS", "HAS_REGION"):
        if busif.parameters.get(key, "0") != "0":
            problems.append(f"interface {busif.name}: {key} on AXI4-Lite, which has no such port")


def _check_directions(busif: Interface, problems: list[str]) -> None:
    roles = LOGICAL_PORTS.get(busif.vlnv, {})
    if busif.vlnv in BUS_TYPES:
        # The direction of the VALID that the slave receives names the mode.
        valid = busif.ports.get("TVALID") or busif.ports.get("AWVALID")
        master = valid is not None and valid.direction == "out"
    else:
        master = False
    for logical, port in busif.ports.items():
        expected = roles.get(logical)
        if expected is None:
            continue
        if master:
            expected = {"in": "out", "out": "in"}[expected]
        if port.direction != expected:
            mode = "master" if master else "slave"
            problems.append(
                f"port {port.name}: {logical} of {mode} interface {busif.name} "
                f"must be '{expected}', is '{port.direction}'"
            )


def problems(top: Top) -> list[str]:
    """Everything wrong with the interface attributes of `top` (empty: none)."""
    found, issues = interfaces(top)
    buses = [b for b in found.values() if b.vlnv in BUS_TYPES]
    clocks = [b for b in found.values() if b.vlnv == CLOCK]
    resets = [b for b in found.values() if b.vlnv == RESET]
    for busif in found.values():
        _check_directions(busif, issues)
        if busif.vlnv in BUS_TYPES and busif.parameter_port is None:
            issues.append(f"interface {busif.name}: no X_INTERFACE_PARAMETER")
        if busif.vlnv == "xilinx.com:interface:axis:1.0":
            _check_axis(busif, issues)
        elif busif.vlnv == "xilinx.com:interface:aximm:1.0":
            _check_aximm(busif, issues)
    if len(clocks) != 1:
        issues.append(f"{len(clocks)} clock interfaces, the checks expect one")
    for clock in clocks:
        named = [n for n in clock.parameters.get("ASSOCIATED_BUSIF", "").split(":") if n]
        for name in sorted(set(named)):
            if named.count(name) > 1:
                issues.append(f"clock {clock.name}: ASSOCIATED_BUSIF names {name} twice")
            if name not in {b.name for b in buses}:
                issues.append(f"clock {clock.name}: ASSOCIATED_BUSIF names {name}, not a bus")
        for busif in buses:
            if busif.name not in named:
                issues.append(f"clock {clock.name}: ASSOCIATED_BUSIF lacks {busif.name}")
        named_resets = [n for n in clock.parameters.get("ASSOCIATED_RESET", "").split(":") if n]
        if sorted(named_resets) != sorted(r.name for r in resets):
            issues.append(
                f"clock {clock.name}: ASSOCIATED_RESET {':'.join(named_resets) or '(none)'}, "
                f"the resets are {':'.join(r.name for r in resets) or '(none)'}"
            )
    for reset in resets:
        polarity = reset.parameters.get("POLARITY")
        if polarity != "ACTIVE_LOW":
            issues.append(f"reset {reset.name}: POLARITY {polarity}, must be ACTIVE_LOW")
    for irq in (b for b in found.values() if b.vlnv == INTERRUPT):
        sensitivity = irq.parameters.get("SENSITIVITY", "LEVEL_HIGH")
        if sensitivity not in {"LEVEL_HIGH", "LEVEL_LOW", "EDGE_RISING", "EDGE_FALLING"}:
            issues.append(f"interrupt {irq.name}: SENSITIVITY {sensitivity}")
    return issues


def load(
    path: Path, entity: str = "fastnms_axi", generics_override: dict[str, str] | None = None
) -> Top:
    return parse(path.read_text(), entity, generics_override)
