"""The Vivado calls of a dry run (tclcheck.dry_run), checked against what
Vivado accepts (vivado_api): `check(calls, ...)` lists every call that names
an unknown command, option, property, CONFIG key or value, pin, VLNV,
automation rule or bus definition, misses a required option or argument, or
gives too many arguments. The stub itself answers anything; this is where a
misspelling fails.

What it cannot see: whether Vivado would accept the values it does not list,
what Vivado returns, and what happens after (validation, synthesis, timing).
"""

from __future__ import annotations

import fnmatch
import re
from dataclasses import dataclass, field

from flows.vivado_check import vivado_api, xinterface
from flows.vivado_check.vivado_api import IP


def tcl_split(text: str) -> list[str]:
    """The words of a Tcl list (braces, double quotes, backslashes)."""
    words, i, n = [], 0, len(text)
    while i < n:
        while i < n and text[i].isspace():
            i += 1
        if i >= n:
            break
        if text[i] == "{":
            depth, j = 1, i + 1
            while j < n and depth:
                if text[j] == "\\":
                    j += 2
                    continue
                depth += {"{": 1, "}": -1}.get(text[j], 0)
                j += 1
            words.append(text[i + 1 : j - 1])
            i = j
            continue
        quoted = text[i] == '"'
        j, word = i + 1 if quoted else i, []
        while j < n and (text[j] != '"' if quoted else not text[j].isspace()):
            if text[j] == "\\" and j + 1 < n:
                word.append(text[j + 1])
                j += 2
                continue
            word.append(text[j])
            j += 1
        words.append("".join(word))
        i = j + 1 if quoted else j
    return words


# ---- command syntax ------------------------------------------------------------------


@dataclass
class Syntax:
    name: str
    options: dict[str, tuple[int, bool, bool]]  # -opt -> (values 0/1, required, repeatable)
    min_args: int
    max_args: float
    arg_names: tuple[str, ...] = ()


def parse_syntax(line: str) -> Syntax:
    name, _, rest = line.partition(" ")
    options: dict[str, tuple[int, bool, bool]] = {}
    min_args, max_args = 0, 0.0
    arg_names: list[str] = []
    token = re.compile(r"\[[^\]]*\](?:\.\.\.)?|-\w+(?:\s+<\w+>)?|<\w+>(?:\.\.\.)?")
    for item in token.findall(rest):
        optional = item.startswith("[")
        variadic = "..." in item
        inner = item.replace("...", "").strip("[]")
        if inner.startswith("-"):
            option, _, value = inner.partition(" ")
            required = not optional and option not in vivado_api.NOT_REQUIRED.get(name, ())
            options[option] = (1 if value else 0, required, value == "<args>")
        else:
            arg_names.append(inner.strip("<>"))
            min_args += 0 if optional else 1
            max_args = float("inf") if variadic else max_args + 1
    return Syntax(name, options, min_args, max_args, tuple(arg_names))


SYNTAX = {s.name: s for s in map(parse_syntax, vivado_api.UG835_SYNTAX + vivado_api.IPX_SYNTAX)}


def parse_call(call: list[str], problems: list[str]) -> tuple[dict[str, list[str]], list[str]]:
    """The options (each with its values) and the arguments of a call; the
    problems with them go to `problems`."""
    command, words = call[0], call[1:]
    syntax = SYNTAX[command]
    options: dict[str, list[str]] = {}
    args: list[str] = []
    i = 0
    while i < len(words):
        word = words[i]
        if word[1:] in syntax.arg_names and word not in syntax.options and i + 1 < len(words):
            # An argument given by its name, as UG835's own examples do
            # (`make_wrapper -files [get_files x.bd] -top`).
            args.append(words[i + 1])
            i += 2
            continue
        if word.startswith("-") and not re.fullmatch(r"-[\d.]+", word):
            spec = syntax.options.get(word)
            if spec is None:
                close = [o for o in syntax.options if o.startswith(word)]
                hint = f" (an abbreviation of {', '.join(close)})" if close else ""
                problems.append(f"{command}: no option {word}{hint}")
                i += 1
                continue
            arity, _, repeatable = spec
            if word in options and not repeatable:
                problems.append(f"{command}: option {word} given twice")
            if arity and i + 1 >= len(words):
                problems.append(f"{command}: option {word} needs a value")
            options.setdefault(word, []).extend(words[i + 1 : i + 1 + arity])
            i += 1 + arity
            continue
        args.append(word)
        i += 1
    for option, (_, required, _) in syntax.options.items():
        if required and option not in options:
            problems.append(f"{command}: the required option {option} is missing")
    min_args = syntax.min_args
    if command == "set_property" and "-dict" in options:
        min_args = 1  # -dict {name value ...} stands for <name> <value> (UG835 set_property)
    if not min_args <= len(args) <= syntax.max_args:
        expected = (
            f"{min_args}" if min_args == syntax.max_args else f"{min_args} to {syntax.max_args}"
        )
        problems.append(f"{command}: {len(args)} arguments {args}, expects {expected}")
    return options, args


# ---- the IP core packaged from the RTL -------------------------------------------------


def top_ip(top: xinterface.Top, vlnv: str) -> IP:
    """The packaged fastnms_axi as the block design sees it: generics as CONFIG
    keys, ports and signal interfaces as pins, bus interfaces as interface
    pins (m_axis_score only with SCORE_VIDEO)."""
    found, _ = xinterface.interfaces(top)
    buses = {n for n, b in found.items() if b.vlnv in xinterface.BUS_TYPES}
    signals = set(found) - buses
    vendor_library_name, _, version = vlnv.rpartition(":")

    def score_video(config: vivado_api.Config, n: int) -> bool:
        return config.get("SCORE_VIDEO", "false").lower() == "true"

    return IP(
        vlnv=vendor_library_name,
        versions=(version,),
        source=f"rtl/top/{top.entity}.vhd",
        config={name.upper(): value for name, value in top.generics.items()},
        values={"SCORE_VIDEO": frozenset({"true", "false"})},
        pins={name: None for name in set(top.ports) | signals},
        intf_pins={n: (score_video if n == "m_axis_score" else None) for n in buses},
    )


# ---- the check -----------------------------------------------------------------------


@dataclass
class Cell:
    ip: IP
    config: dict[str, str] = field(default_factory=dict)  # CONFIG values set, upper-case keys

    def effective(self) -> vivado_api.Config:
        return {**self.ip.config, **self.config}


def _pin_exists(ip: IP, pins: dict, name: str, config: vivado_api.Config) -> bool:
    for template, condition in pins.items():
        if "{" not in template:
            if template == name:
                return condition is None or condition(config, 0)
            continue
        for n in range(64):
            if template.format(n=n) == name and (condition is None or condition(config, n)):
                return True
    return False


def _object(word: str) -> str:
    word = word.strip()
    if word.startswith("{") and word.endswith("}"):
        word = word[1:-1].strip()
    return word


class Checker:
    def __init__(self, ips: dict[str, IP], top: xinterface.Top | None):
        self.ips = ips
        self.top = top
        self.interfaces = xinterface.interfaces(top)[0] if top else {}
        self.cells: dict[str, Cell] = {}
        self.problems: list[str] = []

    def problem(self, call: list[str], text: str) -> None:
        self.problems.append(f"{text}    [{' '.join(call)[:160]}]")

    def ip_of(self, vlnv: str) -> IP | None:
        base, _, version = vlnv.rpartition(":")
        if vlnv in self.ips:
            return self.ips[vlnv]
        ip = self.ips.get(base)
        if ip is not None and version in ip.versions:
            return ip
        return None

    def cell_of(self, word: str) -> Cell | None:
        path = _object(word)
        if re.fullmatch(r"/\w+", path):
            return self.cells.get(path[1:])
        return None

    def kind_of(self, word: str) -> str | None:
        obj = _object(word)
        if obj.startswith("/"):
            return "bd_cell" if re.fullmatch(r"/\w+", obj) else "bd_pin"
        return vivado_api.OBJECT_KINDS.get(obj.split(" ", 1)[0])

    def check_property(self, call: list[str], name: str, value: str | None, obj: str) -> None:
        kind = self.kind_of(obj)
        if kind is None:
            self.problem(call, f"{call[0]} {name}: the stub cannot tell what object {obj} is")
            return
        if kind == "bd_cell" and name.upper().startswith("CONFIG."):
            cell = self.cell_of(obj)
            if cell is None:
                self.problem(call, f"{call[0]}: no cell {_object(obj)} was created")
                return
            key = name.upper().removeprefix("CONFIG.")
            if key not in cell.ip.config:
                self.problem(call, f"{call[0]}: {cell.ip.vlnv} has no CONFIG.{key}")
                return
            if value is None:
                return
            allowed = cell.ip.values.get(key)
            ok = allowed is None or (
                value in allowed
                if isinstance(allowed, frozenset)
                else re.fullmatch(r"\d+", value) is not None and int(value) in allowed
            )
            if not ok:
                shown = sorted(allowed) if isinstance(allowed, frozenset) else allowed
                self.problem(call, f"{call[0]}: CONFIG.{key} {value} not in {shown}")
            cell.config[key] = value
            return
        if name.lower() not in vivado_api.PROPERTIES.get(kind, frozenset()):
            self.problem(call, f"{call[0]}: {kind} objects have no property {name}")

    def check_pin(self, call: list[str], pattern: str, interface: bool) -> None:
        if "*" in pattern or "?" in pattern:
            return
        cell_name, _, pin = pattern.strip("/").partition("/")
        cell = self.cells.get(cell_name)
        if cell is None or not pin:
            self.problem(call, f"{call[0]}: no cell {cell_name} (pin {pattern})")
            return
        pins = cell.ip.intf_pins if interface else cell.ip.pins
        if not _pin_exists(cell.ip, pins, pin, cell.effective()):
            kind = "interface pin" if interface else "pin"
            self.problem(
                call, f"{call[0]}: {cell.ip.vlnv} ({cell_name}) has no {kind} {pin} as configured"
            )

    def check(self, call: list[str]) -> None:
        command = call[0]
        if command not in SYNTAX:
            self.problem(call, f"{command}: not a Vivado command the stub knows")
            return
        problems: list[str] = []
        options, args = parse_call(call, problems)
        for text in problems:
            self.problem(call, text)
        handler = getattr(self, "on_" + command.replace("::", "_"), None)
        if handler is not None:
            handler(call, options, args)

    # -- per command --

    def on_create_bd_cell(self, call, options, args) -> None:
        kind = options.get("-type", ["ip"])[0].lower()
        if kind not in {"ip", "hier", "module", "container", "inline_hdl"}:
            self.problem(call, f"create_bd_cell: -type {kind}")
        if kind != "ip" or not args:
            return
        vlnv = options.get("-vlnv", [""])[0]
        ip = self.ip_of(vlnv)
        if ip is None:
            self.problem(call, f"create_bd_cell: unknown VLNV '{vlnv}'")
            return
        if args[0] in self.cells:
            self.problem(call, f"create_bd_cell: a second cell {args[0]}")
        self.cells[args[0]] = Cell(ip)

    def on_get_bd_cells(self, call, options, args) -> None:
        if "-of_objects" in options:
            return
        for pattern in (p for a in args for p in tcl_split(a)):
            name = pattern.strip("/")
            if not any(c in name for c in "*?") and name not in self.cells:
                self.problem(call, f"get_bd_cells: no cell {name}")

    def on_get_bd_pins(self, call, options, args) -> None:
        if "-of_objects" not in options:
            for pattern in (p for a in args for p in tcl_split(a)):
                self.check_pin(call, pattern, interface=False)

    def on_get_bd_intf_pins(self, call, options, args) -> None:
        if "-of_objects" not in options:
            for pattern in (p for a in args for p in tcl_split(a)):
                self.check_pin(call, pattern, interface=True)

    def on_set_property(self, call, options, args) -> None:
        if "-dict" in options:
            pairs = tcl_split(options["-dict"][0])
            if len(pairs) % 2:
                self.problem(call, "set_property -dict: an odd number of words")
            for obj in args:
                for name, value in zip(pairs[::2], pairs[1::2], strict=False):
                    self.check_property(call, name, value, obj)
            return
        if len(args) >= 3:
            for obj in args[2:]:
                self.check_property(call, args[0], args[1], obj)

    def on_get_property(self, call, options, args) -> None:
        if len(args) == 2:
            self.check_property(call, args[0], None, args[1])

    def on_apply_bd_automation(self, call, options, args) -> None:
        rule = options.get("-rule", [""])[0]
        keys = vivado_api.AUTOMATION_RULES.get(rule)
        if keys is None:
            self.problem(call, f"apply_bd_automation: unknown rule '{rule}'")
            return
        config = tcl_split(options.get("-config", [""])[0])
        for key in config[::2]:
            if key not in keys:
                self.problem(call, f"apply_bd_automation: {rule} has no -config key {key}")

    def on_get_ipdefs(self, call, options, args) -> None:
        for vlnv in args:
            if self.ip_of(vlnv) is None:
                self.problem(call, f"get_ipdefs: unknown VLNV '{vlnv}'")

    def on_ipx_infer_bus_interfaces(self, call, options, args) -> None:
        if args and args[0] not in vivado_api.BUS_DEFINITIONS:
            self.problem(call, f"{call[0]}: unknown bus definition '{args[0]}'")

    def on_ipx_infer_bus_interface(self, call, options, args) -> None:
        if len(args) > 1 and args[1] not in vivado_api.BUS_DEFINITIONS:
            self.problem(call, f"{call[0]}: unknown bus definition '{args[1]}'")

    def _names(self, call, args, known: set[str], what: str) -> None:
        if self.top is None:
            return
        for pattern in (p for a in args for p in tcl_split(a)):
            if not fnmatch.filter(known, pattern):
                self.problem(call, f"{call[0]}: {self.top.entity} has no {what} {pattern}")

    def on_ipx_get_bus_interfaces(self, call, options, args) -> None:
        self._names(call, args, set(self.interfaces), "bus interface")

    def on_ipx_get_ports(self, call, options, args) -> None:
        self._names(call, args, set(self.top.ports) if self.top else set(), "port")

    def on_ipx_get_user_parameters(self, call, options, args) -> None:
        self._names(call, args, set(self.top.generics) if self.top else set(), "generic")

    def on_ipgui_get_guiparamspec(self, call, options, args) -> None:
        names = options.get("-name", [])
        self._names(call, names, set(self.top.generics) if self.top else set(), "generic")

    def on_ipx_get_bus_parameters(self, call, options, args) -> None:
        for name in (p for a in args for p in tcl_split(a)):
            if name.upper() not in vivado_api.BUS_PARAMETERS:
                self.problem(call, f"{call[0]}: unknown bus parameter {name}")

    def on_ipx_associate_bus_interfaces(self, call, options, args) -> None:
        clocks = {n for n, b in self.interfaces.items() if b.vlnv == "xilinx.com:signal:clock:1.0"}
        self._names(call, options.get("-busif", []), set(self.interfaces), "bus interface")
        self._names(call, options.get("-clock", []), clocks, "clock interface")


def check(
    calls: list[list[str]],
    ips: dict[str, IP] | None = None,
    top: xinterface.Top | None = None,
) -> list[str]:
    """The problems of a dry run's Vivado calls (empty: none). `ips` adds IP
    cores to vivado_api.IPS (the packaged top, see top_ip); `top` enables the
    checks of the IP packager's names against the top level."""
    checker = Checker({**vivado_api.IPS, **(ips or {})}, top)
    for call in calls:
        checker.check(call)
    return checker.problems
