"""The one place that imports the native module `_spindrift` and owns the add-on's Renderer.

One Renderer (its own GL thread and EGL context, never Blender's) serves the viewport preview and the final
frames; the module serialises calls on it. It is made on first use and closed when the add-on unregisters.
"""

import threading

_module = None
_import_error = None
_renderer = None
_renderer_error = None
_lock = threading.Lock()


def module():
    """The `_spindrift` module; raises ImportError with the reason if it cannot be loaded."""
    global _module, _import_error
    if _module is None and _import_error is None:
        try:
            from . import _spindrift
            _module = _spindrift
        except ImportError as error:
            _import_error = error
    if _module is None:
        raise ImportError(f"Spindrift's native module did not load: {_import_error}")
    return _module


_table = None


def parameter_table():
    """The parameter table (read once: it is fixed for the module's lifetime)."""
    global _table
    if _table is None:
        _table = module().parameter_table()
    return _table


def status():
    try:
        version = module().__version__
    except ImportError as error:
        return str(error)
    if _renderer is not None:
        return f"{version}, OpenGL {_renderer.gl_version} on {_renderer.gl_renderer}"
    if _renderer_error is not None:
        return f"{version}; the renderer failed: {_renderer_error}"
    return f"{version} (renderer not started)"


def renderer():
    """The shared Renderer, made on first use (any thread). Raises the module's Error if there is no GL."""
    global _renderer, _renderer_error
    with _lock:
        if _renderer is None:
            try:
                _renderer = module().Renderer()
                _renderer_error = None
            except Exception as error:  # noqa: BLE001 - shown to the user, retried next time
                _renderer_error = str(error)
                raise
        return _renderer


def close():
    global _renderer
    with _lock:
        if _renderer is not None:
            _renderer.close()
            _renderer = None
