"""The `fastnms` command line: the top-level parser and main().

Subcommands (`golden`, `sim`, `compare`, `pyramid`) are registered in SUBCOMMANDS; each
gets its own sub-parser and handler, in a module of its own (golden_command, sim_command,
compare_command, pyramid_command). User errors (bad arguments, unreadable images,
unwritable outputs) end as one `fastnms: error: ...` line on stderr with exit status 2 and
leave no output file behind.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence

from fastnms.args import EXIT_USAGE, PROG, ArgumentParser, UsageError
from fastnms.compare_command import add_compare_parser, run_compare
from fastnms.golden_command import add_golden_parser, run_golden
from fastnms.pyramid_command import add_pyramid_parser, run_pyramid
from fastnms.sim_command import add_sim_parser, run_sim

Handler = Callable[[argparse.Namespace], int]
SUBCOMMANDS: dict[str, tuple[Callable[..., argparse.ArgumentParser], Handler]] = {
    "golden": (add_golden_parser, run_golden),
    "sim": (add_sim_parser, run_sim),
    "compare": (add_compare_parser, run_compare),
    "pyramid": (add_pyramid_parser, run_pyramid),
}


def build_parser() -> ArgumentParser:
    parser = ArgumentParser(
        prog=PROG,
        description=(
            "FAST-9/16 corner detection with non-maxima suppression: the golden model, the "
            "RTL in simulation, the comparison of the two, and the golden model's image "
            "pyramid."
        ),
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, (add_parser, handler) in SUBCOMMANDS.items():
        add_parser(sub).set_defaults(handler=handler, command=name)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_USAGE
    try:
        return args.handler(args)
    except UsageError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
