"""The project's flows, each a program of its own with its tests beside it: synthesis and
place and route (`synth`), the simulation bench (`bench`), the results report (`report`),
the register-map generator (`regmap`), the checks of the Vivado scripts (`vivado_check`)
and of the FuseSoC core (`fusesoc`). Run from the repository root: `python -m flows.X.Y`.
"""
