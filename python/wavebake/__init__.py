"""wavebake from Python.

    import wavebake
    store = wavebake.Store("cubes.wbk")          # metadata, samples, columns
    image = wavebake.relight(store, "builtin:sky", terms=256, rotate=30)
    report = wavebake.eval(store, "builtin:sky", reference=True)
    job = wavebake.Client("127.0.0.1:7433").submit("builtin:cubes-wall", light_res=16)

See docs/python.md for a worked example.
"""
from ._wavebake import Client, Store, Watch, bake, eval, relight

__all__ = ["Client", "Store", "Watch", "bake", "eval", "relight"]
