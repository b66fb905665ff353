"""Tcl checks of the Vivado scripts where Vivado is not installed.

A Tcl interpreter comes from Python's tkinter when it imports, else from
`tclsh`. With one, each script is checked command by command (`info complete`)
and can be *dry-run*: sourced for real, with every Vivado command (any command
plain Tcl does not know) answered by a stub that records the call. That runs
the script's own Tcl (variables, procs, expressions, option parsing, paths,
file lists); stubcheck.check then checks the recorded calls against the
commands, options, properties, CONFIG keys, pins and VLNVs Vivado knows
(vivado_api). What Vivado would answer is not checked. Without any
interpreter only a brace/bracket/quote balance check is possible
(`complete_commands_fallback`).
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


# Vivado stubbed: `unknown` answers every command plain Tcl lacks and records
# the call (stubcheck.check then checks it against vivado_api). A result in
# ::stub_results wins: its keys are glob patterns matched, in order, against
# the call's words joined by spaces (a key without a pattern matches the calls
# that start with it). Otherwise block-design objects get Vivado's names
# (create_bd_cell and get_bd_cells give "/cell", get_bd_pins and
# get_bd_intf_pins "/cell/pin"), and any other query (get_*, current_*,
# create_*, make_*, add_*, infer_*) one word that names the call, so that
# later calls show what they were given.
#
# `proc` is wrapped: a script that defines a proc in the global namespace
# fails, as such a proc can hide a Vivado command (a `connect_net` proc once
# hid Vivado's own); procs go in namespace fastnms.
_STUB_PRELUDE = r"""
set ::stub_calls {}
proc ::stub_patterns {args} {
    # The non-option words of a get_bd_* call, list elements flattened.
    set patterns {}
    set skip 0
    foreach a $args {
        if {$skip} {
            set skip 0
        } elseif {$a in {-filter -of_objects}} {
            set skip 1
        } elseif {![string match -* $a]} {
            foreach p $a {
                lappend patterns $p
            }
        }
    }
    return $patterns
}
proc unknown {args} {
    lappend ::stub_calls $args
    set command [lindex $args 0]
    set call [join $args " "]
    dict for {key value} $::stub_results {
        if {$call eq $key || [string match "$key *" $call] || [string match $key $call]} {
            return $value
        }
    }
    set name [namespace tail $command]
    if {$name eq "create_bd_cell"} {
        return "/[lindex $args end]"
    }
    if {$name in {get_bd_cells get_bd_pins get_bd_intf_pins} && "-of_objects" ni $args} {
        set objects {}
        foreach p [::stub_patterns {*}[lrange $args 1 end]] {
            lappend objects "/[string trimleft $p /]"
        }
        return $objects
    }
    if {[regexp {^(get|current|create|make|add|infer)_} $name]} {
        set words {}
        foreach a [lrange $args 1 end] {
            if {![string match -* $a]} {
                lappend words $a
            }
        }
        return [list "[string trimleft $command :] [join $words { }]"]
    }
    return {}
}
proc exit {args} {
    error "the script called exit"
}
rename proc ::stub_proc
::stub_proc proc {name arguments body} {
    set space [uplevel 1 {namespace current}]
    if {[string match ::* $name]} {
        set full $name
    } else {
        set full [string trimright $space :]::$name
    }
    if {[namespace qualifiers $full] eq ""} {
        error "tclcheck: proc '$name' in the global namespace could hide a Vivado\
            command: define it in namespace fastnms"
    }
    uplevel 1 [list ::stub_proc $name $arguments $body]
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
