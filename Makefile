# `make dist`: the C ABI (crates/uwml-ffi) as one package per target, for C firmware built
# without Rust (docs/firmware.md, "Without Rust"). Building a package needs cargo and the target's
# standard library (`rustup target add thumbv7em-none-eabihf`); using one needs a C compiler only.
#
#   make dist                                  every target of TARGETS
#   make dist TARGETS=thumbv7em-none-eabihf    one of them
#   make dist DIST=/tmp/packages               elsewhere than dist/
#
# Each target gives $(DIST)/uwml-<version>-<target>/ and its .tar.gz: include/uwml.h,
# lib/libuwml.a, lib/pkgconfig/uwml.pc, lib/cmake/uwml/uwmlConfig{,Version}.cmake (the imported
# target uwml::uwml), examples/ (minimal.c, its Makefile and CMakeLists.txt) and README.md, made
# from crates/uwml-ffi/package/. Cargo builds into CARGO_TARGET_DIR (default target/).

VERSION := $(shell sed -n 's/^version = "\(.*\)"$$/\1/p' Cargo.toml)
HOST := $(shell rustc -vV | sed -n 's/^host: //p')
TARGETS ?= $(HOST) thumbv7em-none-eabihf
DIST ?= dist
CARGO ?= cargo
CARGO_TARGET_DIR ?= target
export CARGO_TARGET_DIR

# The system libraries the archive needs, as rustc names them (`cargo rustc ... -- --print
# native-static-libs`): none on bare metal. Another hosted target needs its own line.
LIBS_x86_64-unknown-linux-gnu := -lgcc_s -lutil -lrt -lpthread -lm -ldl -lc

TEMPLATES := crates/uwml-ffi/package
space := $(subst ,, )

# In a target's recipe ($* is the target).
package = $(DIST)/uwml-$(VERSION)-$*
libs = $(LIBS_$*)
pointer_bytes = $(shell echo $$(( $$(rustc --print cfg --target $* | sed -n 's/^target_pointer_width="\(.*\)"/\1/p') / 8 )))
fill = sed -e 's|@VERSION@|$(VERSION)|g' -e 's|@TARGET@|$*|g' -e 's| *@LIBS@|$(if $(libs), $(libs))|g' \
	-e 's|@CMAKE_LIBS@|$(subst $(space),;,$(patsubst -l%,%,$(libs)))|g' \
	-e 's|@MAJOR_MINOR@|$(basename $(VERSION))|g' -e 's|@POINTER_BYTES@|$(pointer_bytes)|g'

.PHONY: dist $(addprefix dist-,$(TARGETS))
dist: $(addprefix dist-,$(TARGETS))

# One crate type only (`--crate-type staticlib`): then the release profile's fat LTO makes the
# whole library one object, with nothing of the crates but what the C functions reach. Bare-metal
# targets abort on panic (their default; the library's handler spins, and nothing panics).
$(addprefix dist-,$(TARGETS)): dist-%:
	$(CARGO) rustc -q --release -p uwml-ffi --lib --crate-type staticlib --target $*
	rm -rf $(package) $(package).tar.gz
	mkdir -p $(package)/include $(package)/lib/pkgconfig $(package)/lib/cmake/uwml $(package)/examples
	cp crates/uwml-ffi/include/uwml.h $(package)/include/
	cp $(CARGO_TARGET_DIR)/$*/release/libuwml_ffi.a $(package)/lib/libuwml.a
	cp $(TEMPLATES)/examples/minimal.c $(TEMPLATES)/examples/Makefile $(TEMPLATES)/examples/CMakeLists.txt \
		$(package)/examples/
	$(fill) $(TEMPLATES)/README.md.in > $(package)/README.md
	$(fill) $(TEMPLATES)/uwml.pc.in > $(package)/lib/pkgconfig/uwml.pc
	$(fill) $(TEMPLATES)/uwmlConfig.cmake.in > $(package)/lib/cmake/uwml/uwmlConfig.cmake
	$(fill) $(TEMPLATES)/uwmlConfigVersion.cmake.in > $(package)/lib/cmake/uwml/uwmlConfigVersion.cmake
	tar -C $(DIST) -czf $(package).tar.gz uwml-$(VERSION)-$*
	@echo "$(package).tar.gz: $$(wc -c < $(package).tar.gz) bytes; lib/libuwml.a $$(wc -c < $(package)/lib/libuwml.a) bytes"
