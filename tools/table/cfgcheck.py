"""Test helpers for `python -m tools.<module> table --config` (tests/<module>/*_cfg_test.py): run the
command as a user would, on shipped or inline configurations, and check its image or its error."""
import contextlib
import importlib
import io
import os
import re
import shutil
import tempfile


def run(args):
    """(exit code, stdout + stderr) of `python -m MODULE ARGS...` (args[0] the module), run in this
    process through the module's own main(argv) (the same argparse path, without a new
    interpreter and its numpy/scipy imports for every case)."""
    main = importlib.import_module(args[0] + ".__main__").main
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(buf):
        try:
            rc = main(list(args[1:]))
        except SystemExit as e:
            rc = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
            if e.code is not None and not isinstance(e.code, int):
                print(e.code)
    return rc, buf.getvalue()


def table(module, config, image, revision=None):
    args = ["tools.%s" % module, "table", "--config", config, "-o", image]
    if revision is not None:
        args += ["--revision", str(revision)]
    return run(args)


def builtin_image(module, name, image, revision=None):
    args = ["tools.%s" % module, "image", "--table", name, "-o", image]
    if revision is not None:
        args += ["--revision", str(revision)]
    return run(args)


class Suite(object):
    """Checks of one module's table command; prints each, then 'N passed, N failed'."""

    def __init__(self, module):
        self.module = module
        self.tmp = tempfile.mkdtemp(prefix="cfgtest_")
        self.n_ok = 0
        self.n_bad = 0

    def check(self, name, ok, detail=""):
        print("%-4s %s%s" % ("ok" if ok else "FAIL", name, ("\n       " + detail.replace("\n", "\n       "))
                                                             if detail and not ok else ""))
        if ok:
            self.n_ok += 1
        else:
            self.n_bad += 1
        return ok

    def path(self, name):
        return os.path.join(self.tmp, name)

    def same_as_builtin(self, config, builtin, revision=None):
        """The configuration's image is byte-identical to the built-in table's image."""
        a, b = self.path("cfg.bin"), self.path("builtin.bin")
        for p in (a, b):
            if os.path.exists(p):
                os.remove(p)
        rc1, out1 = table(self.module, config, a, revision)
        rc2, out2 = builtin_image(self.module, builtin, b, revision)
        ok = rc1 == 0 and rc2 == 0 and open(a, "rb").read() == open(b, "rb").read()
        return self.check("%s reproduces %s%s byte for byte" % (os.path.basename(config), builtin,
                                                                (" (revision %d)" % revision) if revision else ""),
                          ok, out1 + out2)

    def builds(self, config):
        img = self.path("ok.bin")
        if os.path.exists(img):
            os.remove(img)
        rc, out = table(self.module, config, img)
        self.check("%s builds an image" % os.path.basename(config), rc == 0 and os.path.exists(img), out)
        return open(img, "rb").read() if rc == 0 and os.path.exists(img) else None

    def bad(self, label, yaml_text, patterns):
        """An invalid configuration: exit code 2, no image, and every regex of patterns in the output."""
        cfg, img = self.path("bad.yaml"), self.path("bad.bin")
        with open(cfg, "w", encoding="utf-8") as fh:
            fh.write(yaml_text)
        if os.path.exists(img):
            os.remove(img)
        rc, out = table(self.module, cfg, img)
        missing = [p for p in patterns if not re.search(p, out)]
        ok = rc == 2 and not os.path.exists(img) and not missing
        self.check("rejects %s" % label, ok, "exit %d, image %s, missing %s; output:\n%s"
                   % (rc, "written" if os.path.exists(img) else "not written", missing, out))
        if ok:
            print("       " + "\n       ".join(l for l in out.splitlines() if l.startswith(cfg)).replace(cfg, "CFG"))
        return ok

    def done(self):
        shutil.rmtree(self.tmp, ignore_errors=True)
        print("%d passed, %d failed" % (self.n_ok, self.n_bad))
        return 1 if self.n_bad else 0
