"""What the VTK peer scripts (vtk-mesh-peer, vtk-volume-peer) share."""
import os
import shutil
import sys


def reexec_under_xvfb(script, screen):
    """Re-runs `script` under xvfb-run with a `screen` (WxHxD) display when there is none:
    Debian's VTK opens an X display even offscreen."""
    if os.environ.get("DISPLAY") or os.environ.get("VTK_PEER_XVFB"):
        return
    name = os.path.basename(script)
    if not shutil.which("xvfb-run"):
        sys.exit("%s: no DISPLAY and no xvfb-run (apt-get install xvfb)" % name)
    env = dict(os.environ, VTK_PEER_XVFB="1")
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 " + screen, sys.executable,
           os.path.abspath(script)] + sys.argv[1:]
    os.execvpe(cmd[0], cmd, env)
