import os, json
import cocotb, numpy as np
from cocotb.triggers import RisingEdge, ReadOnly
from tb.nms.region_tb import TB, map_beats
from fastnms.testing.regions import SHAPES, grid

@cocotb.test()
async def dbg(dut):
    tb = TB(dut)
    await tb.reset()
    name = os.environ.get("DBG_SHAPE", "u")
    c, s = grid(SHAPES[name][0])
    tb.set_cfg(width=c.shape[1])
    async def mon():
        while True:
            await RisingEdge(dut.clk)
            await ReadOnly()
            try:
                print(int(cocotb.utils.get_sim_time("ns")), "CLK cstep=%s lock=%s rstep=%s cx=%d rcol=%d p0=%s pm=%s row_rd=%s depth=%d primed=%s fl=%s ahead=%d last=%d cy=%d c0=%s cm=%s act=%s att=%s" % (
                    dut.cstep.value, dut.lock.value, dut.rstep.value, int(dut.cx.value), int(dut.rcol.value),
                    dut.p0.value, dut.pm.value, dut.row_rd.value, int(dut.depth.value), dut.primed.value, dut.flushing.value,
                    int(dut.r_ahead.value), int(dut.r_lastcol.value), int(dut.cy.value), dut.px_corner.value, dut.cm.value, dut.active.value, dut.attached.value))
            except Exception as e:
                print("CLK ?", e)
    cocotb.start_soon(mon())
    from tb.nms.region_tb import stress_maps
    maps = stress_maps(32, np.random.default_rng(1))
    print("MAPS", [m[0].shape for m in maps])
    await tb.run_maps(maps, "x")
