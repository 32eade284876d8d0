"""Builds the Blender add-on's zip: ``sylva_tree/__init__.py`` and the sylva package unpacked
from a built wheel into ``sylva_tree/vendor/`` (Blender cannot load a compiled module from
inside a zip, so the wheel is unpacked, not copied).

    python build_addon.py dist/sylva-*.whl sylva_tree.zip
"""

import os
import sys
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))


def build(wheel: str, out: str) -> None:
    with zipfile.ZipFile(wheel) as whl, zipfile.ZipFile(out + ".part", "w", zipfile.ZIP_DEFLATED) as z:
        z.write(os.path.join(HERE, "sylva_tree", "__init__.py"), "sylva_tree/__init__.py")
        packaged = [n for n in whl.namelist() if n.startswith("sylva/")]
        if not any(n.startswith("sylva/_sylva") and n.endswith(".so") for n in packaged):
            sys.exit(f"{wheel}: no compiled sylva module in it; is it a sylva wheel?")
        for name in packaged:
            z.writestr("sylva_tree/vendor/" + name, whl.read(name))
    os.replace(out + ".part", out)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: build_addon.py WHEEL OUT.zip")
    build(sys.argv[1], sys.argv[2])
