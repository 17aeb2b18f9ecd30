"""Prints where the contactlab package goes under the install prefix argv[1], relative to it:
Debian's lib/python3/dist-packages for /usr (the .deb), lib/python3.X/dist-packages for
/usr/local (both on Debian's sys.path), the prefix's site-packages otherwise (named by
PYTHONPATH). Run by cmake/install.cmake at install time, with the interpreter the module is
built for."""

import sys
import sysconfig

prefix = sys.argv[1].rstrip("/") or "/"
schemes = sysconfig.get_scheme_names()
if prefix == "/usr" and "deb_system" in schemes:
    scheme, base = "deb_system", prefix
elif prefix == "/usr/local" and "posix_local" in schemes:
    scheme, base = "posix_local", "/usr"  # posix_local adds the local/ itself
else:
    scheme, base = "posix_prefix", prefix
path = sysconfig.get_path("platlib", scheme, vars={"platbase": base, "base": base})
print(path[len(prefix):].lstrip("/") if path.startswith(prefix + "/") else path, end="")
