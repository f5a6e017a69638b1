"""stage_lite.model.warmup leaves no kernel of the model, nor of Stage's controllers, to
compile at a stageros's start.

warm() runs in a fresh interpreter; then every kernel Python calls (a numba function no other
kernel calls) must have been compiled or loaded from numba's cache. A kernel that only other
kernels call is compiled into them (and shows no signature of its own when they come from
the cache), so it is covered by its callers.
"""
import json
import subprocess
import sys

import pytest

pytest.importorskip('numba')

CHECK = '''
import importlib, inspect, json, pkgutil, re
import stage_lite.controllers as controllers
import stage_lite.model as model
from stage_lite.model import warmup
warmup.warm()
kernels = {}
for package in (model, controllers):
  for info in pkgutil.iter_modules(package.__path__):
    module = importlib.import_module(package.__name__ + '.' + info.name)
    for name, obj in vars(module).items():
        if getattr(obj, 'py_func', None) is not None and obj.py_func.__module__ == module.__name__:
            kernels['%s.%s' % (info.name, name)] = obj
sources = {key: inspect.getsource(k.py_func) for key, k in kernels.items()}
called = {key for key in kernels for other, text in sources.items() if other != key
          and re.search(r'\\b%s\\(' % re.escape(key.split('.')[1]), text)}
print(json.dumps({'kernels': sorted(kernels),
                  'left': sorted(key for key, k in kernels.items()
                                 if not k.signatures and key not in called)}))
'''


def test_warm_compiles_every_kernel_python_calls():
    out = subprocess.run([sys.executable, '-c', CHECK], capture_output=True, text=True,
                         check=True).stdout
    result = json.loads(out.strip().splitlines()[-1])
    assert {'grid.move', 'grid.redraw', 'raytrace.cast_scans', 'raytrace.cast_scans_parallel',
            'raytrace.trace', 'image._trace', '_avoid._beam_rule'} <= set(result['kernels'])
    assert result['left'] == [], 'warmup.warm() never calls %s' % result['left']


def test_a_change_to_any_source_drops_every_cached_kernel(tmp_path):
    from stage_lite.model.warmup import drop_stale_kernels
    pkg = tmp_path / 'pkg'
    (pkg / 'model' / '__pycache__').mkdir(parents=True)
    (pkg / 'model' / 'grid.py').write_text('def move(): return 1\n')
    (pkg / 'model' / 'motion.py').write_text('def move_robots(): return 2\n')

    def cached():
        path = pkg / 'model' / '__pycache__' / 'motion.move_robots-9.py311.nbi'
        path.write_bytes(b'kernel')
        return path
    first = cached()
    assert drop_stale_kernels(str(pkg)) == 1 and not first.exists()   # no digest yet
    kept = cached()
    assert drop_stale_kernels(str(pkg)) == 0 and kept.exists()        # nothing changed
    # motion's own file untouched, the file its kernel compiles in changed
    (pkg / 'model' / 'grid.py').write_text('def move(): return 3\n')
    assert drop_stale_kernels(str(pkg)) == 1 and not kept.exists()
