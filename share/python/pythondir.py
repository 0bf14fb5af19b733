# SPDX-License-Identifier: GPL-3.0-or-later
"""The folder make install puts the qusgm package in, for PREFIX (argv[1]): where the python3
that runs this finds it.  PREFIX=/usr on Debian: /usr/lib/python3/dist-packages, Debian's own
folder for every python3 version; otherwise the entry of sys.path under PREFIX/lib (Debian's
/usr/local/lib/python3.X/dist-packages for PREFIX=/usr/local); otherwise the site-packages of
the standard scheme under PREFIX, which that python does not search: PYTHONPATH must name it
(share/doc/library.md, "Reading packs and tables in Python")."""
import os
import sys
import sysconfig

prefix = os.path.normpath(sys.argv[1])
debian = "/usr/lib/python3/dist-packages"
if prefix == "/usr" and debian in sys.path:
    print(debian)
else:
    for d in sys.path:
        if d.startswith(prefix + "/lib/") and d.endswith(("site-packages", "dist-packages")):
            print(d)
            break
    else:
        print(sysconfig.get_path("purelib", "posix_prefix", {"base": prefix, "platbase": prefix}))
