"""Scene files: a TOML description of a cracked part, planar or solid, read
into a ``cracklip.Scene``.

One schema (``SCHEMA``) lists every key with its type, default and meaning;
the parser accepts exactly these keys and the scene reference is generated
from it (``reference_markdown()``, or ``python3 -m cracklip reference``). An
unknown key is an ``InputError`` naming the nearest valid key. Typical use::

    from cracklip.io.scene_file import load_scene_file
    sf = load_scene_file("demos/scenes/block_uniform_pressure.toml", overrides=["mesh.h=0.1"])
    solution = cracklip.solve(sf.scene)

Paths in the schema: ``mesh.h`` is key ``h`` of table ``[mesh]``;
``cracks[].points`` is key ``points`` of every ``[[cracks]]`` entry;
``loads.tractions[].kirsch.remote_stress`` is a key of the inline table
``kirsch = {...}`` of a ``[[loads.tractions]]`` entry.

One module per section of the schema, each with its keys and what they
build: ``mesh`` ([mesh]), ``material`` ([units], [material]), ``cracks``
([[cracks]]), ``conditions`` ([[dirichlet]], [loads], [[load_path]]),
``options`` ([options], [outputs]), ``growth`` ([growth],
[material.fatigue] with its da/dN table file, [spectrum]), ``life``
([life], the life without a mesh that cracklip.io.life_file reads);
``schema`` the machinery of keys and parsers, ``dimension`` which keys a
2D or a 3D scene takes, ``reader`` the whole schema and its checks,
``build`` the Scene.
"""
from .build import SceneFile, build_scene, load_scene_file
from .options import add_option_arguments
from .reader import (KEYS, SCHEMA, TABLES, apply_override, check_keys, parse_settings, read_document,
                     reference_markdown, reference_rows)
from .schema import REQUIRED, UNSET, Key

__all__ = ["SceneFile", "build_scene", "load_scene_file", "add_option_arguments", "KEYS", "SCHEMA", "TABLES",
           "apply_override", "check_keys", "parse_settings", "read_document", "reference_markdown", "reference_rows",
           "REQUIRED", "UNSET", "Key"]
