# SPDX-License-Identifier: GPL-3.0-or-later
# blender_addon: the _conica CPython extension and the installable add-on zip.
#
#   make blender-addon   ->  $(BUILD)/conica-blender.zip
#
# Built against CPython's stable ABI at 3.11 (-DPy_LIMITED_API=0x030B0000,
# see ext/_conica.c for why 3.11), so the one _conica.abi3.so loads in
# every Blender whose Python is 3.11 or later on this platform: Debian's
# 3.4 and official 4.1-5.x. Only the headers matter, and any 3.11+ headers
# give the same ABI; python3-config is taken from /usr/bin, never from PATH
# (a pyenv or venv may have no headers). libconica is linked in
# statically and its symbols hidden (--exclude-libs), so the add-on needs
# no libconica on the user's machine. LAPACKE, which libcore uses for its
# SVD fit, is linked statically too; the LAPACK/BLAS it calls stay dynamic
# (--as-needed): Debian's blender package itself depends on liblapack3 and
# libblas3, so every Blender that can load this module already has them.
# (On Windows the same module is `_conica.pyd`, see docs/blender.md.)
BLENDER_PYCONFIG ?= /usr/bin/python3-config
BLENDER_PY_INC   := $(sort $(shell $(BLENDER_PYCONFIG) --includes 2>/dev/null))
BLENDER_PY_LIMITED := 0x030B0000
BLENDER_PY_EXT   := .abi3.so
# The platform the binary is for, in the manifest's words (linux-x64,
# macos-arm64, ...): the staged blender_manifest.toml lists this one.
BLENDER_OS   := $(subst Linux,linux,$(subst Darwin,macos,$(shell uname -s)))
BLENDER_ARCH := $(subst x86_64,x64,$(subst aarch64,arm64,$(shell uname -m)))
BLENDER_PLATFORM ?= $(BLENDER_OS)-$(BLENDER_ARCH)

BLENDER_STAGE := $(BUILD)/blender/conica
BLENDER_EXT   := $(BLENDER_STAGE)/_conica$(BLENDER_PY_EXT)
BLENDER_ZIP   := $(BUILD)/conica-blender.zip
BLENDER_PKG_SRCS := $(wildcard blender_addon/conica/*.py blender_addon/conica/*.toml) blender_addon/conica/LICENSE
BLENDER_EXT_OBJ := $(BUILD)/obj/blender_addon/ext/_conica.o

# Python.h is included as a system header (-isystem): its inline functions
# trip -Wconversion/-Wpedantic inside CPython's own headers, which we cannot
# change; our own code still compiles with the full project warning set.
$(BLENDER_EXT_OBJ): CPPFLAGS += $(patsubst -I%,-isystem %,$(BLENDER_PY_INC)) \
    -DPy_LIMITED_API=$(BLENDER_PY_LIMITED)

$(BLENDER_EXT): $(BLENDER_EXT_OBJ) $(CORE_A)
	@mkdir -p $(@D)
	rm -f $(@D)/_conica.cpython-*.so
	$(CC) -shared $(LDFLAGS) -o $@ $(BLENDER_EXT_OBJ) $(CORE_A) \
	  -Wl,--exclude-libs,ALL -Wl,--no-undefined-version \
	  -Wl,-Bstatic -llapacke -Wl,-Bdynamic -Wl,--as-needed -llapack -lblas -lm -Wl,--no-as-needed

$(BLENDER_STAGE)/blender_manifest.toml: blender_addon/conica/blender_manifest.toml blender_addon/module.mk
	@mkdir -p $(@D)
	sed 's/^platforms = .*/platforms = ["$(BLENDER_PLATFORM)"]/' $< >$@.tmp
	mv $@.tmp $@

$(BLENDER_STAGE)/%: blender_addon/conica/%
	@mkdir -p $(@D)
	cp $< $@

BLENDER_STAGED := $(BLENDER_EXT) $(BLENDER_PKG_SRCS:blender_addon/conica/%=$(BLENDER_STAGE)/%)

# Exactly the staged files go into the zip (a stale file left in the stage
# by a renamed source does not), under conica/ as Blender expects.
$(BLENDER_ZIP): $(BLENDER_STAGED)
	rm -f $@.tmp
	$(BLENDER_PYCONFIG:-config=) -c 'import sys, zipfile, os; \
	  z = zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_DEFLATED); \
	  [z.write(f, os.path.join("conica", os.path.basename(f))) for f in sorted(sys.argv[2:])]; \
	  z.close()' $@.tmp $(BLENDER_STAGED)
	mv $@.tmp $@

blender-addon: $(BLENDER_ZIP)

TEST_EXTRA += $(BLENDER_ZIP)
DEMO_DEPS  += $(BLENDER_ZIP)

.PHONY: blender-addon

# scripts/bench-blender.sh (run by `make bench`) loads the zip.
bench: $(BLENDER_ZIP)
