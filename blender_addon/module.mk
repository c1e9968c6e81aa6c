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

# The staged manifest lists the platform of its stage's binary (PLATFORM,
# set per stage: this one's, windows-x64 for the Windows stage below).
define BLENDER_MANIFEST_RECIPE
	@mkdir -p $(@D)
	sed 's/^platforms = .*/platforms = ["$(PLATFORM)"]/' $< >$@.tmp
	mv $@.tmp $@
endef
$(BLENDER_STAGE)/blender_manifest.toml: PLATFORM := $(BLENDER_PLATFORM)
$(BLENDER_STAGE)/blender_manifest.toml: blender_addon/conica/blender_manifest.toml blender_addon/module.mk
	$(BLENDER_MANIFEST_RECIPE)

$(BLENDER_STAGE)/%: blender_addon/conica/%
	@mkdir -p $(@D)
	cp $< $@

BLENDER_STAGED := $(BLENDER_EXT) $(BLENDER_PKG_SRCS:blender_addon/conica/%=$(BLENDER_STAGE)/%)

# Exactly the staged files (the prerequisites) go into the zip (a stale file
# left in the stage by a renamed source does not), under conica/ as
# Blender expects.
define BLENDER_ZIP_RECIPE
	rm -f $@.tmp
	$(BLENDER_PYCONFIG:-config=) -c 'import sys, zipfile, os; \
	  z = zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_DEFLATED); \
	  [z.write(f, os.path.join("conica", os.path.basename(f))) for f in sorted(sys.argv[2:])]; \
	  z.close()' $@.tmp $^
	mv $@.tmp $@
endef

$(BLENDER_ZIP): $(BLENDER_STAGED)
	$(BLENDER_ZIP_RECIPE)

blender-addon: $(BLENDER_ZIP)

TEST_EXTRA += $(BLENDER_ZIP)
DEMO_DEPS  += $(BLENDER_ZIP)

.PHONY: blender-addon

# scripts/bench-blender.sh (run by `make bench`) loads the zip.
bench: $(BLENDER_ZIP)

# ---------------------------------------------------------------- Windows
#
#   make blender-extension-windows  ->  $(BUILD)/conica-blender-windows-x64.zip
#
# The same package for Windows x64 (Blender 4.2+), cross-compiled here with
# Debian's MinGW-w64 (gcc-mingw-w64-x86-64, gfortran-mingw-w64-x86-64;
# scripts/deps.sh windows): _conica.pyd against CPython's limited API at
# 3.11, linked to python3.dll only, through an import library made from
# tests/blender/stable_abi.txt with dlltool (so a symbol outside the stable
# ABI cannot even link). The CPython headers are those of Debian's
# python3.11 source package with its Windows pyconfig.h (PC/pyconfig.h);
# LAPACK(E) is compiled from Debian's lapack source package, only the
# routines libconica reaches (tools/windows-lapack.sh), and linked in
# statically with the Fortran and thread runtimes: the .pyd imports
# python3.dll and Windows' own DLLs and nothing else (tests/cli/blender.sh
# checks). No -mfma: Blender 4.2 runs on x86-64 CPUs without FMA, and
# MinGW-w64's fma() is exact in software. Nothing of it runs here (no
# Windows); docs/blender.md says what was checked.
WIN_CROSS  ?= x86_64-w64-mingw32
WIN_CC     := $(WIN_CROSS)-gcc-win32
WIN_DIR    := $(BUILD)/windows
WIN_STAGE  := $(WIN_DIR)/stage/conica
WIN_PYD    := $(WIN_STAGE)/_conica.pyd
WIN_ZIP    := $(BUILD)/conica-blender-windows-x64.zip
WIN_LAPACK := $(WIN_DIR)/lapack/liblapacke.a
WIN_PYINC  := $(WIN_DIR)/python/Include
# the MinGW headers' isfinite() casts to float inside the macro, which
# -Wfloat-conversion flags in every caller; the Linux build keeps the check
WIN_CFLAGS := -O2 $(WARN) -Wno-float-conversion -fvisibility=hidden \
    -D__USE_MINGW_ANSI_STDIO=1 -DMS_WIN64 -Ilibcore/include
WIN_CORE_OBJS := $(CORE_SRCS:libcore/src/%.c=$(WIN_DIR)/obj/%.o)

$(WIN_DIR)/src/lapack.stamp: blender_addon/tools/debian-source.sh
	rm -rf $(WIN_DIR)/src/lapack && mkdir -p $(WIN_DIR)/src/lapack
	sh blender_addon/tools/debian-source.sh lapack $(WIN_DIR)/src/lapack
	touch $@

$(WIN_DIR)/src/python.stamp: blender_addon/tools/debian-source.sh
	rm -rf $(WIN_DIR)/src/python && mkdir -p $(WIN_DIR)/src/python
	sh blender_addon/tools/debian-source.sh python3.11 $(WIN_DIR)/src/python --download-only
	touch $@

# Include/ and PC/pyconfig.h of the CPython source (Debian's orig tarball)
$(WIN_PYINC)/pyconfig.h: $(WIN_DIR)/src/python.stamp
	rm -rf $(WIN_DIR)/python && mkdir -p $(WIN_DIR)/python
	tar -xzf $(WIN_DIR)/src/python/python3.11_*.orig.tar.gz -C $(WIN_DIR)/python \
	  --strip-components=1 --wildcards '*/Include' '*/PC/pyconfig.h'
	cp $(WIN_DIR)/python/PC/pyconfig.h $@

$(WIN_LAPACK): $(WIN_DIR)/src/lapack.stamp blender_addon/tools/windows-lapack.sh $(CORE_SRCS)
	sh blender_addon/tools/windows-lapack.sh $(WIN_DIR)/src/lapack/lapack-*/ $(WIN_DIR)/lapack

# python3.dll's import library: every name of the stable ABI list, data
# names (exception objects, type objects, singletons) marked DATA
$(WIN_DIR)/libpython3.a: tests/blender/stable_abi.txt
	@mkdir -p $(@D)
	{ echo "LIBRARY python3.dll"; echo "EXPORTS"; grep -v '^#' $< | grep . | \
	  awk '/^(PyExc_|_Py_.*Struct$$|Py.*_Type$$|_PyWeakref_.*Type$$|Py_FileSystemDefaultEncod|Py_HasFileSystemDefaultEncoding|Py_UTF8Mode|PyStructSequence_UnnamedField|_Py_SwappedOp)/ \
	    {print $$1 " DATA"; next} {print}'; } >$(WIN_DIR)/python3.def
	$(WIN_CROSS)-dlltool -d $(WIN_DIR)/python3.def -D python3.dll -l $@

$(WIN_DIR)/obj/%.o: libcore/src/%.c $(WIN_LAPACK)
	@mkdir -p $(@D)
	$(WIN_CC) $(WIN_CFLAGS) -Ilibcore/src -DCONICA_BUILDING -I$(WIN_DIR)/lapack/include -c $< -o $@

$(WIN_DIR)/obj/_conica.o: blender_addon/ext/_conica.c $(WIN_PYINC)/pyconfig.h
	@mkdir -p $(@D)
	$(WIN_CC) $(WIN_CFLAGS) -isystem $(WIN_PYINC) -DPy_LIMITED_API=$(BLENDER_PY_LIMITED) -c $< -o $@

$(WIN_PYD): $(WIN_DIR)/obj/_conica.o $(WIN_CORE_OBJS) $(WIN_LAPACK) $(WIN_DIR)/libpython3.a
	@mkdir -p $(@D)
	$(WIN_CC) -shared -o $@ $(WIN_DIR)/obj/_conica.o $(WIN_CORE_OBJS) $(WIN_LAPACK) \
	  -L$(WIN_DIR) -lpython3 -static-libgcc -Wl,--exclude-libs,ALL \
	  -Wl,-Bstatic -lgfortran -lquadmath -lwinpthread -Wl,-Bdynamic

$(WIN_STAGE)/blender_manifest.toml: PLATFORM := windows-x64
$(WIN_STAGE)/blender_manifest.toml: blender_addon/conica/blender_manifest.toml blender_addon/module.mk
	$(BLENDER_MANIFEST_RECIPE)

$(WIN_STAGE)/%: blender_addon/conica/%
	@mkdir -p $(@D)
	cp $< $@

WIN_STAGED := $(WIN_PYD) $(BLENDER_PKG_SRCS:blender_addon/conica/%=$(WIN_STAGE)/%)

$(WIN_ZIP): $(WIN_STAGED)
	$(BLENDER_ZIP_RECIPE)

blender-extension-windows: $(WIN_ZIP)

# `make tests` builds it where the cross compiler is installed (scripts/deps.sh
# test installs it; the Debian source packages come from the mirror)
ifneq ($(shell command -v $(WIN_CC) 2>/dev/null),)
TEST_EXTRA += $(WIN_ZIP)
endif

.PHONY: blender-extension-windows
