#!/usr/bin/python3
"""Writes a damaged copy of a dem checkpoint, for tests/test_scene.c (bad input: checkpoints are not trusted).

usage: tests/craft_checkpoint.py GOOD.ckpt.h5 OUT.ckpt.h5 VARIANT
VARIANT: step_negative, step_past_end, step_huge, n_huge, n_mismatch, hist_dropped, scene_frictionless, pairs_out_of_range,
pairs_huge, text_varlen, step_array, model_array, text_array, path_array, wall_pos_nan, spin_inf, v_nan,
radius_zero, order_bad; and order_unrecorded, a checkpoint as written before the particles' order was recorded (it
must restart in the scene's order). Each other one is a file a careless reader would act on: allocate on its claims, restart at a time the scene
never reaches, or write saved memory that does not fit the run.
"""
import shutil
import sys

import h5py
import numpy as np


def main():
    good, out, variant = sys.argv[1:4]
    shutil.copyfile(good, out)
    with h5py.File(out, "r+") as f:
        st = f["state"]
        if variant == "step_negative":
            st.attrs["step"] = -5
        elif variant == "step_past_end":
            st.attrs["step"] = 10 ** 6
        elif variant == "step_huge":
            st.attrs["step"] = 10 ** 14
        elif variant == "n_huge":
            st.attrs["n"] = 10 ** 12
        elif variant == "n_mismatch":
            st.attrs["n"] = int(st.attrs["n"]) - 1
        elif variant == "hist_dropped":  # claims no friction memory while the scene has friction
            st.attrs["has_hist"] = 0
            del st["wall_hist"]
            st.create_dataset("wall_hist", data=np.zeros(0))
        elif variant == "scene_frictionless":  # the stored scene lost friction; the memory is still there
            text = f["scene/text"][()].decode()
            text = text.replace("friction, ", "").replace("friction: 0.4", "friction: 0")
            raw = text.encode()
            del f["scene/text"]
            f["scene"].create_dataset("text", data=np.array(raw, dtype=f"S{len(raw) + 1}"))
        elif variant == "order_unrecorded":  # as written before particle_order had a default of spatial: no attribute,
            # and a scene without the key (the run in the scene's order, which the default was then)
            del f["scene"].attrs["particle_order"]
            text = f["scene/text"][()].decode()
            raw = "".join(l for l in text.splitlines(True) if not l.startswith("particle_order:")).encode()
            del f["scene/text"]
            f["scene"].create_dataset("text", data=np.array(raw, dtype=f"S{len(raw) + 1}"))
        elif variant == "order_bad":
            f["scene"].attrs["particle_order"] = "random"
        elif variant == "pairs_out_of_range":
            p = st["pair_i"][:]
            p[0] = 10 ** 6
            st["pair_i"][:] = p
        elif variant == "pairs_huge":  # a dataset that claims far more pairs than any packing can have
            del st["pair_i"]
            st.create_dataset("pair_i", shape=(10 ** 9,), dtype="i4")  # no storage: fill value
        elif variant == "step_array":  # an attribute that is an array: read into one long, it would overrun it
            del st.attrs["step"]
            st.attrs["step"] = np.arange(1000, dtype="i8")
        elif variant == "model_array":
            f["scene"].attrs["model"] = np.array([b"mc_strain"] * 1000)
        elif variant == "text_varlen":  # the scene text as a variable-length string (read as a pointer before)
            text = f["scene/text"][()]
            del f["scene/text"]
            f["scene"].create_dataset("text", data=text.decode(), dtype=h5py.string_dtype())
        elif variant in ("text_array", "path_array"):  # an array of strings where one is read (heap overrun before)
            name = variant.split("_")[0]
            one = f["scene/" + name][()]
            del f["scene/" + name]
            f["scene"].create_dataset(name, data=np.array([one] * 1000))
        elif variant == "wall_pos_nan":  # a wall that would silently stop acting
            p = st["wall_pos"][:]
            p[0, 2] = np.nan
            st["wall_pos"][:] = p
        elif variant == "spin_inf":
            w = st["w"][:]
            w[3, 1] = np.inf
            st["w"][:] = w
        elif variant == "v_nan":  # failed at step 10 with exit 1 before
            v = st["v"][:]
            v[5, 0] = np.nan
            st["v"][:] = v
        elif variant == "radius_zero":
            r = st["radius"][:]
            r[2] = 0
            st["radius"][:] = r
        else:
            sys.exit(f"craft_checkpoint: unknown variant {variant}")


if __name__ == "__main__":
    main()
