"""Results several test processes need, made once per machine: `make test` runs the tests not marked ros on two
pytest-xdist workers and the ros tests beside them, three processes that on a clean clone would each build the same
cached file (the default model's watch reference at 5 mm: ~30 s of one core) at the same time. Each builder takes an
exclusive lock on a file beside the cache entry first; the others wait, then read what it wrote."""
from backlash_monitor.files.locks import exclusive


def watch_reference(model):
    """``reference.cached(model)`` -- the model's watch reference from the cache, built there when missing -- built
    by one process only: the others wait for it and load the file."""
    from backlash_monitor.workbench import reference
    path = reference.cache_path(model)
    with exclusive(path.with_name(path.name + ".lock")):
        return reference.cached(model)
