"""Draws a DXF file's model space to PNG with ezdxf's drawing add-on (matplotlib backend), as a
reader of Sylva's DXF files sees them: `python3 tools/dxf-png.py plan.dxf plan.png 12 12`
(width and height in inches, at 110 dpi). Needs `pip install ezdxf matplotlib`. A grown tree's
plan and elevations (some 200,000 entities) take matplotlib some two minutes."""
import sys, ezdxf
import matplotlib; matplotlib.use('Agg')
import matplotlib.pyplot as plt
from ezdxf.addons.drawing import RenderContext, Frontend
from ezdxf.addons.drawing.config import Configuration, BackgroundPolicy, LineweightPolicy
from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
src, out = sys.argv[1], sys.argv[2]
w, h = (float(sys.argv[3]), float(sys.argv[4])) if len(sys.argv) > 4 else (12.0, 8.0)
doc = ezdxf.readfile(src)
fig = plt.figure(figsize=(w, h))
ax = fig.add_axes([0.01, 0.01, 0.98, 0.98])
cfg = Configuration(background_policy=BackgroundPolicy.WHITE, lineweight_policy=LineweightPolicy.ABSOLUTE, min_lineweight=0.35)
Frontend(RenderContext(doc), MatplotlibBackend(ax), config=cfg).draw_layout(doc.modelspace(), finalize=True)
fig.savefig(out, dpi=110, facecolor='white')
