"""fastnms: a streaming FAST-9/16 corner detector with non-maxima suppression for FPGAs.

The Python side of the IP, one package from several folders of the repository:

- `fastnms.golden` (golden/): the golden model, the contract the RTL is checked against;
- `fastnms.main` (cli/): the `fastnms` command line, with a module per subcommand
  (`golden_command`, `sim_command`, `compare_command`, `pyramid_command`) and the shared
  arguments, inputs, outputs, PNG overlay and RTL run beside it;
- `fastnms.sim` (sim/): runs the AXI top under GHDL on an image (needs rtl/ beside it);
- `fastnms.testing` (testing/): test images, corner-map shapes, seeds and pytest fixtures
  shared by the golden tests, the testbenches and the flows.
"""
