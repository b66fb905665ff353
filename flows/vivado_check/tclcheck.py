"""Tcl checks of the Vivado scripts where Vivado is not installed.

A Tcl interpreter comes from Python's tkinter when it imports, else from
`tclsh`. With one, each script is checked command by command (`info complete`)
and can be *dry-run*: sourced for real, with every Vivado command (any command
plain Tcl does not know) answered by a stub that records the call. That checks
the script's own Tcl (variables, procs, expressions, option parsing, paths,
file lists) and the Vivado commands and arguments it issues, not what Vivado
would answer. Without any interpreter only a brace/bracket/quote balance check
is possible (`complete_commands_fallback`).
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from pathlib import Path

_SEP_WORD = "\x1f"
_SEP_CALL = "\x1e"


def backend() -> str | None:
    """'tkinter', 'tclsh' or None."""
    try:
        import tkinter

        tkinter.Tcl()
        return "tkinter"
    except Exception:
        pass
    return "tclsh" if shutil.which("tclsh") else None


class TclError(Exception):
    """A Tcl error; the message is Tcl's errorInfo (message and stack)."""


def run_tcl(script: str) -> str:
    """Evaluates `script` in a fresh interpreter and returns its result."""
    kind = backend()
    if kind is None:
        raise RuntimeError("no Tcl interpreter (neither tkinter nor tclsh)")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "driver.tcl"
        path.write_text(script)
        if kind == "tkinter":
            import tkinter

            interp = tkinter.Tcl()
            try:
                return str(interp.eval(f"source {{{path}}}"))
            except tkinter.TclError as err:
                raise TclError(str(interp.eval("set ::errorInfo"))) from err
        # The result goes to a file: stdout carries what the script prints.
        wrapper = Path(tmp) / "wrapper.tcl"
        result = Path(tmp) / "result.txt"
        # (exit is renamed first: the dry-run stubs replace it.)
        wrapper.write_text(
            "rename exit __tclcheck_exit\n"
            f"set code [catch {{source {{{path}}}}} result]\n"
            f"set f [open {{{result}}} w]\n"
            "puts -nonewline $f [expr {$code == 1 ? $::errorInfo : $result}]\n"
            "close $f\n"
            "__tclcheck_exit [expr {$code == 1}]\n"
        )
        proc = subprocess.run(["tclsh", str(wrapper)], capture_output=True, text=True)
        print(proc.stdout, end="")
        if proc.returncode:
            raise TclError(result.read_text() if result.exists() else proc.stderr)
        return result.read_text()


def incomplete_commands(path: Path) -> list[str]:
    """The commands of a Tcl file that `info complete` rejects (with their first
    line numbers); empty when every command is complete."""
    script = f"""
        set f [open {{{path}}} r]
        set text [read $f]
        close $f
        set bad {{}}
        set command {{}}
        set start 1
        set number 0
        foreach line [split $text "\\n"] {{
            incr number
            if {{$command eq {{}}}} {{
                set start $number
            }}
            append command $line "\\n"
            if {{[info complete $command]}} {{
                set command {{}}
            }}
        }}
        if {{$command ne {{}}}} {{
            lappend bad "line $start: [string range [string trim $command] 0 60]"
        }}
        join $bad "\\n"
    """
    out = run_tcl(script)
    return out.splitlines() if out else []


def complete_commands_fallback(text: str) -> list[str]:
    """Without Tcl: the problems of a crude balance check of braces, brackets
    and double quotes (backslash escapes and comments honoured)."""
    problems = []
    depth = 0  # braces
    brackets = 0
    quoted = False
    at_command_start = True
    line = 1
    i = 0
    while i < len(text):
        c = text[i]
        if c == "\\":
            i += 2
            continue
        if c == "\n":
            line += 1
        if at_command_start and depth == 0 and not quoted and c == "#":
            while i < len(text) and text[i] != "\n":
                i += 2 if text[i] == "\\" else 1
            continue
        if depth:
            depth += {"{": 1, "}": -1}.get(c, 0)
        elif c == '"':
            quoted = not quoted
        elif quoted and c in "{}":
            pass
        elif c == "{":
            depth = 1
        elif c == "[":
            brackets += 1
        elif c == "]":
            brackets -= 1
            if brackets < 0:
                problems.append(f"line {line}: unmatched ]")
                brackets = 0
        elif c == "}":
            problems.append(f"line {line}: unmatched }}")
        at_command_start = c in "\n;" or (at_command_start and c in " \t")
        i += 1
    if depth or brackets or quoted:
        problems.append(f"end of file: {depth} open braces, {brackets} brackets, quote {quoted}")
    return problems


# Vivado stubbed: `unknown` answers every command plain Tcl lacks. A query
# (get_*, current_*, create_*, make_*, ipx::get_*, ...) returns one word that
# names the call, so that later calls show what they were given; a result
# set in ::stub_results (by "command first-argument" or by command) wins.
_STUB_PRELUDE = r"""
set ::stub_calls {}
proc unknown {args} {
    lappend ::stub_calls $args
    set command [lindex $args 0]
    set key "$command [lindex $args 1]"
    if {[dict exists $::stub_results $key]} {
        return [dict get $::stub_results $key]
    }
    if {[dict exists $::stub_results $command]} {
        return [dict get $::stub_results $command]
    }
    set name [namespace tail $command]
    if {[regexp {^(get|current|create|make|add|infer)_} $name]} {
        set words {}
        foreach a [lrange $args 1 end] {
            if {![string match -* $a]} {
                lappend words $a
            }
        }
        return [list "$name [join $words { }]"]
    }
    return {}
}
proc exit {args} {
    error "the script called exit"
}
"""


def dry_run(
    script: Path, argv: list[str], results: dict[str, str] | None = None
) -> tuple[list[list[str]], str | None]:
    """Sources `script` with ::argv = `argv` and Vivado stubbed out; returns the
    Vivado calls in order (each a list of words) and the Tcl error message, or
    None when the script ran to its end."""
    stub_results = " ".join(
        "{" + key + "} {" + value + "}" for key, value in (results or {}).items()
    )
    argv_words = " ".join("{" + a + "}" for a in argv)
    driver = f"""
        set ::stub_results [dict create {stub_results}]
        {_STUB_PRELUDE}
        set ::argv [list {argv_words}]
        set ::argc [llength $::argv]
        set error {{}}
        if {{[catch {{source {{{script}}}}} message]}} {{
            set error $message
        }}
        set calls {{}}
        foreach call $::stub_calls {{
            lappend calls [join $call "{_SEP_WORD}"]
        }}
        return "$error{_SEP_CALL}[join $calls "{_SEP_CALL}"]"
    """
    out = run_tcl(driver)
    error, *calls = out.split(_SEP_CALL)
    return [c.split(_SEP_WORD) for c in calls if c], (error or None)


# Tcl 8.6 additions, absent from the Tcl 8.5 of older Vivado releases.
TCL86_ONLY = ("lmap", "try", "tailcall", "coroutine", "yield", "zlib", "string cat", "dict map")
