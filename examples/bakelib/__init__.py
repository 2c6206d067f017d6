"""Helpers shared by the examples' bake scripts and the tests' Blender fixtures.

Each example's `bake.py` keeps only its layout (a `Layout`) and its objects (`build_scene`); everything else is
here, in one module per concern:

- `blender_scene`: an empty scene, boxes, planes, materials, the camera and the lighting;
- `mantaflow`: the liquid domain's settings, flow objects, baking and checking the cache;
- `render`: Cycles settings and the example's two renders (background, and with Mantaflow's liquid mesh);
- `scene_file`: the Spindrift scene files written beside the bake;
- `example`: `Layout` and `main`, the command line every example's bake.py runs.

Blender runs a script by path, so a script imports this package after putting `examples/` on `sys.path`
(`examples/dam_break/bake.py` shows the two lines).
"""
