#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Reads a runnel checkpoint (docs/hdf5-schema.md) with h5py and prints a summary.

    python3 docs/python/read_checkpoint.py out/default/final.h5
"""
import sys

import h5py
import numpy as np


def text(value):
    """runnel writes fixed-length UTF-8 strings; h5py returns them as bytes."""
    return value.decode() if isinstance(value, bytes) else str(value)


def main(path):
    with h5py.File(path, "r") as f:
        assert f.attrs["schema_version"] == 3, "this script reads schema version 3"
        terrain = f["terrain"]
        height = terrain["height"][()]  # (ny, nx) float32, metres
        cell = terrain.attrs["cell"]
        eroded = terrain["eroded"][()]
        deposited = terrain["deposited"][()]
        particles = f["particles"]
        xyz = np.stack([particles[k][()] for k in ("x", "y", "z")], axis=1)  # (n, 3), metres
        speed = np.linalg.norm(np.stack([particles[k][()] for k in ("vx", "vy", "vz")], axis=1), axis=1)
        sediment_m3 = particles["sediment"][()] * particles.attrs["sediment_quantum_m3"]
        state = f["state"]
        print(f"model {text(f.attrs['model'])}, runnel {text(f.attrs['runnel_version'])}")
        print(f"terrain {height.shape[1]} x {height.shape[0]}, cell {cell} m, "
              f"heights {height.min():.3f} .. {height.max():.3f} m")
        print(f"eroded {eroded.sum() * cell * cell:.6g} m3, deposited {deposited.sum() * cell * cell:.6g} m3")
        print(f"step {state.attrs['steps']}, t = {state.attrs['time']:.6g} s, {len(xyz)} particles")
        if len(xyz):
            print(f"mean speed {speed.mean():.4g} m/s, suspended sediment {sediment_m3.sum():.6g} m3")
        if "fields" in f:  # grid models: water depth, suspended sediment, ...
            for name, field in f["fields"].items():
                print(f"field {name}: shape {field.shape}, sum {field[()].sum():.6g}")
        # An attribute, or a dataset of that name when the set exceeds an attribute's 64 KiB.
        params = text(f.attrs["parameters_toml"] if "parameters_toml" in f.attrs else f["parameters_toml"][()])
        print(f"parameters: {len(params.splitlines())} lines of TOML")


if __name__ == "__main__":
    main(sys.argv[1])
