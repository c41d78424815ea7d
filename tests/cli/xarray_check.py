"""Optional check (run by test_hdf5.sh only when xarray and h5netcdf are importable): a touchdown
HDF5 file opens in xarray with named dimensions, one shared time axis, and text attributes as str.
Usage: python3 xarray_check.py FILE.h5"""
import sys

import h5py
import xarray as xr

path = sys.argv[1]
with h5py.File(path, "r") as f:
    for name in ("status", "case_text", "library_version"):
        assert isinstance(f.attrs[name], str), (name, type(f.attrs[name]))
    assert isinstance(f["retainers/normal_force"].attrs["units"], str)
    n = f["time"].shape[0]

root = xr.open_dataset(path, engine="h5netcdf")
ret = xr.open_dataset(path, engine="h5netcdf", group="retainers")
nodes = xr.open_dataset(path, engine="h5netcdf", group="nodes")
ambs = xr.open_dataset(path, engine="h5netcdf", group="ambs")
assert root.sizes["time"] == n and root["time"].dims == ("time",), root
assert ret["normal_force"].dims == ("time", "retainer"), ret["normal_force"].dims
assert ret["contact_state"].dims == ("time", "retainer")
assert nodes["displacement"].dims == ("time", "node", "component"), nodes["displacement"].dims
assert ambs["force"].dims == ("time", "amb", "component"), ambs["force"].dims
assert list(root["component"].values) == ["x", "y"], root["component"].values
assert root["events"].dims == ("event",)
assert isinstance(root.attrs["case_text"], str)
print(f"time {n}, retainers {ret.sizes['retainer']}, nodes {nodes.sizes['node']}, events {root.sizes['event']}")
