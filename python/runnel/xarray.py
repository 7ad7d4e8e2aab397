# SPDX-License-Identifier: MIT
"""A model's state as an xarray Dataset in the conventions of `runnel export --format netcdf`
(CF-1.8): dimensions time, y, x; x and y at the pixels' centres in the terrain's map coordinates;
the CRS as the grid mapping variable spatial_ref; height, dh and water_depth in metres."""
import numpy as np


def model_to_xarray(model):
    """The model's state now as an xarray Dataset (one time).

    Parameters
    ----------
    model : Model

    Returns
    -------
    xarray.Dataset
        height (the exact heights), dh (their change from the initial terrain) and, for a grid
        model with water, water_depth, each (time, y, x) in metres, NaN at the terrain's NODATA
        holes; coordinates x, y (pixel
        centres) and time (the model's clock: for a clock in seconds a datetime on the export's
        nominal epoch, 1970-01-01, as xarray decodes the NetCDF export; years and iterations as
        numbers, their units in the attribute).
    """
    import xarray as xr

    initial = model.initial_terrain()
    nx, ny, cell = initial.nx, initial.ny, initial.cell
    x = initial.origin_x + (np.arange(nx) + 0.5) * cell
    y = initial.origin_z + (ny - 0.5 - np.arange(ny)) * cell  # row 0 the northern row
    height = model.elevation()
    fields = {
        "height": (height, "terrain height", "surface_altitude"),
        "dh": (height - initial.heights.astype(np.float64),
               "height change from the initial terrain (erosion < 0, deposition > 0)", None),
    }
    if "surface_water__depth" in model.field_names():
        fields["water_depth"] = (model.field("surface_water__depth"), "depth of the water on the surface", None)
    projected = bool(initial.crs_wkt)
    holes = initial.holes  # NaN there, as xarray reads the export's _FillValue
    data_vars = {}
    for name, (values, long_name, standard_name) in fields.items():
        values = np.where(holes, np.nan, np.asarray(values, dtype=np.float64))
        attrs = {"units": "m", "long_name": long_name}
        if standard_name:
            attrs["standard_name"] = standard_name
        if projected:
            attrs["grid_mapping"] = "spatial_ref"
        data_vars[name] = (("time", "y", "x"), np.asarray(values, dtype=np.float32)[np.newaxis], attrs)
    from . import _runnel

    clock_units = {"s": "s", "yr": "yr", "iterations": "1"}[model.clock]
    time_attrs = _runnel._cf_time_attributes(clock_units)
    time = float(model.time)
    if clock_units == "s":  # a CF time coordinate: xarray decodes it as it decodes the export's
        time = np.datetime64("1970-01-01T00:00:00") + np.timedelta64(int(round(time * 1e9)), "ns")
        time_attrs = {k: v for k, v in time_attrs.items() if k not in ("units", "calendar")}
    coords = {
        "time": ("time", [time], time_attrs),
        "y": ("y", y, {"units": "m", "axis": "Y", "long_name": "northing of the pixel centres",
                       **({"standard_name": "projection_y_coordinate"} if projected else {})}),
        "x": ("x", x, {"units": "m", "axis": "X", "long_name": "easting of the pixel centres",
                       **({"standard_name": "projection_x_coordinate"} if projected else {})}),
    }
    if projected:
        coords["spatial_ref"] = ((), 0, {**_runnel._cf_grid_mapping(initial.crs_wkt),
                                        "crs_wkt": initial.crs_wkt, "spatial_ref": initial.crs_wkt})
    return xr.Dataset(data_vars, coords=coords,
                      attrs={"Conventions": "CF-1.8", "title": "runnel terrain", "source": "runnel"})
