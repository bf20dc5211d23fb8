#!/usr/bin/python3
"""Read (and, for tests, write) impact3d HDF5 dumps.

Layout (docs: docs/design.md, section 6; root attribute `format_version`):

    root attributes   time, cycle, title, units, format_version
    /mesh/coordinates nnode x 3      /mesh/connectivity nzone x 8 (0-based)
    /mesh/block       nzone
    /nodes/velocity   nnode x 3      /nodes/mass        nnode
    /zones/density, specific_internal_energy, pressure, viscosity,
          sound_speed, volume, mass                     nzone each
    optional: /zones/deviatoric_stress (nzone x 6), /zones/plastic_strain,
              /zones/damage (failure), /zones/alive (erosion: 1 live, 0
              eroded), /mesh/live_connectivity (erosion: nzone x 8, an
              eroded zone's corners all its first node),
              /restart/..., /run/... (not read here)

load(path) returns a flat dict: 'coordinates', 'connectivity', 'block',
'live_connectivity' (erosion only),
'node_velocity', 'node_mass', 'density', 'specific_internal_energy',
'pressure', 'viscosity', 'sound_speed', 'volume', 'mass' (zone mass), any
other dataset under /zones by its name, and 'attrs' (dict of root attributes
with strings decoded and one-element arrays made scalars).

Run as a script: print a summary of a dump.
"""

import sys

import h5py
import numpy as np

MESH_FIELDS = {"coordinates": "coordinates", "connectivity": "connectivity",
               "block": "block", "live_connectivity": "live_connectivity"}
NODE_FIELDS = {"velocity": "node_velocity", "mass": "node_mass"}


def _attribute(value):
    """Decode an HDF5 attribute: bytes -> str (stripped), size-1 -> scalar."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace").rstrip("\x00 ").strip()
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "SO" and value.size == 1:
            return _attribute(value.reshape(-1)[0])
        if value.size == 1:
            return value.reshape(-1)[0].item()
        return value
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, str):
        return value.rstrip("\x00 ").strip()
    return value


def _rows(array, width):
    """Return array as (n, width): accept a transposed (width, n) layout."""
    array = np.asarray(array)
    if array.ndim == 2 and array.shape[1] != width and array.shape[0] == width:
        array = array.T
    if array.ndim != 2 or array.shape[1] != width:
        raise ValueError(f"expected an n x {width} dataset, got shape {array.shape}")
    return np.ascontiguousarray(array)


def load(path):
    """Read a dump into a dict of numpy arrays plus 'attrs'."""
    data = {}
    with h5py.File(path, "r") as handle:
        data["attrs"] = {key: _attribute(value) for key, value in handle.attrs.items()}
        for name, key in MESH_FIELDS.items():
            if f"mesh/{name}" in handle:
                data[key] = handle[f"mesh/{name}"][()]
        for name, key in NODE_FIELDS.items():
            if f"nodes/{name}" in handle:
                data[key] = handle[f"nodes/{name}"][()]
        if "zones" in handle:
            for name, dataset in handle["zones"].items():
                if isinstance(dataset, h5py.Dataset):
                    data[name] = dataset[()]
    if "coordinates" not in data or "connectivity" not in data:
        raise ValueError(f"{path}: not an impact3d dump (no /mesh/coordinates "
                         "or /mesh/connectivity)")
    data["coordinates"] = _rows(data["coordinates"], 3).astype(float)
    data["connectivity"] = _rows(data["connectivity"], 8).astype(np.int64)
    if "live_connectivity" in data:
        data["live_connectivity"] = _rows(data["live_connectivity"], 8).astype(np.int64)
    if "node_velocity" in data:
        data["node_velocity"] = _rows(data["node_velocity"], 3).astype(float)
    if "deviatoric_stress" in data:
        data["deviatoric_stress"] = _rows(data["deviatoric_stress"], 6)
    nnode = data["coordinates"].shape[0]
    conn = data["connectivity"]
    if conn.size and (conn.min() < 0 or conn.max() >= nnode):
        raise ValueError(f"{path}: connectivity indices outside [0, {nnode})")
    nzone = conn.shape[0]
    if "mass" not in data and "density" in data and "volume" in data:
        data["mass"] = data["density"] * data["volume"]
    for key, value in data.items():
        if key in ("attrs", "coordinates", "connectivity", "live_connectivity", "node_velocity",
                   "node_mass", "deviatoric_stress"):
            continue
        if np.ndim(value) >= 1 and np.shape(value)[0] != nzone:
            raise ValueError(f"{path}: zone field {key} has {np.shape(value)[0]} "
                             f"rows, expected {nzone}")
    return data


def problem_time(data):
    """Problem time of a loaded dump (root attribute 'time')."""
    return float(data["attrs"]["time"])


def zone_centroids(data):
    """Mean of the 8 node coordinates of each zone (nzone x 3)."""
    return data["coordinates"][data["connectivity"]].mean(axis=1)


def zone_velocity(data):
    """Mean of the 8 node velocities of each zone (nzone x 3)."""
    return data["node_velocity"][data["connectivity"]].mean(axis=1)


def radius(points, origin=(0.0, 0.0, 0.0)):
    """Distance of points (n x 3) from origin."""
    return np.linalg.norm(np.asarray(points) - np.asarray(origin, dtype=float), axis=1)


def write(path, coordinates, connectivity, zones, node_velocity=None,
          node_mass=None, block=None, attrs=None):
    """Write a dump in the impact3d layout (used by tests and examples).

    zones: dict name -> nzone array (density, specific_internal_energy,
    pressure, volume, mass, ...).  Missing node velocity/mass are zeros,
    missing block ids are 1, attributes default to time 0, cycle 0.
    """
    coordinates = np.asarray(coordinates, dtype=float)
    connectivity = np.asarray(connectivity, dtype=np.int32)
    nnode, nzone = coordinates.shape[0], connectivity.shape[0]
    if node_velocity is None:
        node_velocity = np.zeros((nnode, 3))
    if node_mass is None:
        node_mass = np.zeros(nnode)
    if block is None:
        block = np.ones(nzone, dtype=np.int32)
    base = {"time": 0.0, "cycle": 0, "title": "", "units": "", "format_version": 1}
    base.update(attrs or {})
    with h5py.File(path, "w") as handle:
        for key, value in base.items():
            handle.attrs[key] = value
        handle.create_dataset("mesh/coordinates", data=coordinates)
        handle.create_dataset("mesh/connectivity", data=connectivity)
        handle.create_dataset("mesh/block", data=np.asarray(block, dtype=np.int32))
        handle.create_dataset("nodes/velocity", data=np.asarray(node_velocity, dtype=float))
        handle.create_dataset("nodes/mass", data=np.asarray(node_mass, dtype=float))
        for name, value in zones.items():
            handle.create_dataset(f"zones/{name}", data=np.asarray(value))


def main(argv=None):
    """Print the attributes and dataset sizes of a dump."""
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print("usage: dump.py dump.h5", file=sys.stderr)
        return 2
    data = load(argv[0])
    for key, value in data["attrs"].items():
        print(f"{key} = {value}")
    for key, value in data.items():
        if key != "attrs":
            print(f"{key}: shape {np.shape(value)}, dtype {np.asarray(value).dtype}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
