import sys, numpy as np
from benchmarks.balancer import batch_inputs, case, SETUP, CRITERION
from rotorvib.models.balancer import engine
from rotorvib.models.balancer.simulate import run_batch
p, y0 = case()
params, y0s = batch_inputs(p, y0, 300)
m = run_batch(engine.FIXED, params, y0s, CRITERION, progress=False, **SETUP.tolerances)
ms = run_batch(engine.FIXED, params, y0s, CRITERION, progress=False, stop=SETUP.stop, **SETUP.tolerances)
out = np.concatenate([m, ms])
if sys.argv[1] == "save":
    np.save("/tmp/ident.npy", out)
else:
    ref = np.load("/tmp/ident.npy")
    print("identical:", np.array_equal(ref, out, equal_nan=True), "max diff", np.nanmax(np.abs(ref - out)))
