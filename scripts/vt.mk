# vt.mk: GNU make rules for vtpipe content builds (docs/content-builds.md).
#
#   include path/to/vt.mk
#   $(call vt_scene,city,assets/city.obj,build/city)
#   all: $(VT_TARGETS)
#
# builds, for each scene NAME from SCENE.obj into OUTDIR:
#   OUTDIR/NAME.atlas.json   vt-atlas SCENE.obj (the layout; OUTDIR/NAME.atlas.d lists every file read)
#   OUTDIR/NAME.vts          vt-tiles --layout: every layer of the atlas in one store
#   OUTDIR/NAME.vt.obj/.mtl  vt-offset: the scene with atlas texture coordinates, one material
#   OUTDIR/NAME.D.vts        vt-convert, for each delivery D in VT_DELIVERY (optional)
#   OUTDIR/NAME*.vts.ok      stamps of vt-info --verify (set VT_VERIFY to empty to skip)
# and a phony target vt-NAME. Needs GNU make 4.3 or later (grouped targets).
#
# Dependencies: the atlas is rebuilt when SCENE.obj or any file vt-atlas read (MTL files, textures)
# is newer; it replaces NAME.atlas.json only when the layout changed, so touching a texture
# rebuilds the store (which reads the texels) but not the OBJ (which only needs the layout).
# Running make again with nothing changed runs nothing. Every file is written by exactly one rule,
# and the tools write atomically (temporary file + rename), so make -j and an interrupted make are
# safe: the next make finishes the job.

ifeq ($(filter grouped-target,$(.FEATURES)),)
$(error vt.mk needs GNU make 4.3 or later (grouped targets))
endif

# Where vt.mk lives (for scripts/mesh-clean next to it).
VT_MK_DIR := $(dir $(lastword $(MAKEFILE_LIST)))

# Tools: VT_BIN is a directory holding all of them (e.g. build/release/tools); empty: from PATH.
VT_BIN ?=
vt_tool = $(if $(VT_BIN),$(patsubst %/,%,$(VT_BIN))/)$(1)
VT_ATLAS ?= $(call vt_tool,vt-atlas)
VT_OFFSET ?= $(call vt_tool,vt-offset)
VT_TILES ?= $(call vt_tool,vt-tiles)
VT_CONVERT ?= $(call vt_tool,vt-convert)
VT_INFO ?= $(call vt_tool,vt-info)

# Options for every scene; NAME_ATLAS_FLAGS, NAME_TILES_FLAGS... add to them for scene NAME.
VT_ATLAS_FLAGS ?=
VT_TILES_FLAGS ?=
VT_OFFSET_FLAGS ?=
VT_CONVERT_FLAGS ?=
VT_INFO_FLAGS ?=
# Deliveries: for each D, NAME.D.vts = vt-convert NAME.vts --codec D. A store of several layers
# often needs a codec per layer (jpeg and bc1 cannot store alpha, bc3 needs RGBA...): then set
# VT_D_LAYERS (or NAME_D_LAYERS) to a list of LAYER:CODEC, e.g. VT_gpu_LAYERS := 0:bc3 1:bc1;
# layers not listed are copied as they are. The first delivery is the store the rewritten MTL
# names; without any, it names NAME.vts.
VT_DELIVERY ?=
# Non-empty: verify every store with vt-info --verify (stamp NAME.vts.ok).
VT_VERIFY ?= 1

# Optional mesh preparation (docs/mesh-clean.md): SCENE.clean.obj from SCENE.obj with MeshLab
# (duplicate vertices merged; VT_MESH_CLEAN_FLAGS = --simplify 0.5 also simplifies), texture
# coordinates and materials checked face by face. Without MeshLab the scene is copied, with a
# message. Pass SCENE.clean.obj as the scene of vt_scene to use it.
VT_MESH_CLEAN ?= $(VT_MK_DIR)mesh-clean
VT_MESH_CLEAN_FLAGS ?=
%.clean.obj: %.obj
	VT_BIN='$(VT_BIN)' $(VT_MESH_CLEAN) $(VT_MESH_CLEAN_FLAGS) $< $@

# Every target the vt_scene calls defined (vt-NAME for each scene).
VT_TARGETS :=
# Every file the rules write, for a clean rule: rm -f $(VT_OUTPUTS).
VT_OUTPUTS :=

# Rewrites the make dependency line of vt-atlas --deps ("atlas.json: a.obj a.mtl t.png ...",
# possibly continued with backslashes): the layout stamp (awk variable a) depends on every file,
# the store (awk variable s) on the textures only (not the .obj/.mtl files: the layout stands for
# them), and each file gets an empty rule (so that a deleted texture re-runs vt-atlas, which then
# names it, instead of stopping make with "no rule to make target").
VT_DEPS_AWK = { sub(/\r$$/, ""); if (sub(/\\$$/, "")) { l = l $$0 " "; next } l = l $$0 " " } \
  END { i = index(l, ":"); n = i ? split(substr(l, i + 1), p, " ") : 0; \
        printf "%s:", a; for (k = 1; k <= n; k++) printf " %s", p[k]; printf "\n"; \
        printf "%s:", s; for (k = 1; k <= n; k++) if (tolower(p[k]) !~ /\.(obj|mtl)$$/) printf " %s", p[k]; \
        printf "\n"; for (k = 1; k <= n; k++) printf "%s:\n", p[k] }

# $(call vt_track,FILE,TEXT): writes TEXT into FILE unless FILE already holds it, so that FILE's
# date tells when TEXT last changed. Used for the command lines of each step (NAME.*.cmd): a rule
# that depends on one reruns when its tool or options change.
vt_same = $(and $(findstring x$(1)x,x$(2)x),$(findstring x$(2)x,x$(1)x))
vt_track = $(if $(call vt_same,$(file <$(1)),$(strip $(2))),,$(shell mkdir -p $(dir $(1)))$(file >$(1),$(strip $(2))))

# $(call vt_layers,NAME,D): the layer list of delivery D for scene NAME (NAME_D_LAYERS, else
# VT_D_LAYERS).
vt_layers = $(strip $(if $($(1)_$(2)_LAYERS),$($(1)_$(2)_LAYERS),$(VT_$(2)_LAYERS)))

# $(call vt_scene,NAME,SCENE.obj,OUTDIR): defines the rules above for one scene. Set the VT_*
# variables before the call: the command lines are recorded when it runs.
vt_scene = $(eval $(call vt_scene_rules,$(strip $(1)),$(strip $(2)),$(patsubst %/,%,$(strip $(3))),$(firstword $(VT_DELIVERY))))

# $(1) NAME, $(2) SCENE.obj, $(3) OUTDIR, $(4) first delivery codec.
define vt_scene_rules
$(call vt_track,$(3)/$(1).atlas.cmd,$(VT_ATLAS) $(VT_ATLAS_FLAGS) $($(1)_ATLAS_FLAGS))
$(call vt_track,$(3)/$(1).tiles.cmd,$(VT_TILES) $(VT_TILES_FLAGS) $($(1)_TILES_FLAGS))
$(call vt_track,$(3)/$(1).offset.cmd,$(VT_OFFSET) $(VT_OFFSET_FLAGS) $($(1)_OFFSET_FLAGS) $(4))
$(foreach c,$(VT_DELIVERY),$(call vt_track,$(3)/$(1).$(c).cmd,$(VT_CONVERT) $(VT_CONVERT_FLAGS) $($(1)_CONVERT_FLAGS) $($(1)_$(c)_FLAGS) $(call vt_layers,$(1),$(c))))

# The layout. vt-atlas writes NAME.atlas.json.new and NAME.atlas.d.new (atomically); the .new
# layout replaces the old one only when different, so that its date says when the layout changed.
$(3)/$(1).atlas.stamp: $(2) $(3)/$(1).atlas.cmd
	@mkdir -p $(3)
	$$(VT_ATLAS) $(2) -o $(3)/$(1).atlas.json.new --deps $(3)/$(1).atlas.d.new $$(VT_ATLAS_FLAGS) $$($(1)_ATLAS_FLAGS)
	@awk -v a='$(3)/$(1).atlas.stamp' -v s='$(3)/$(1).vts' '$$(VT_DEPS_AWK)' $(3)/$(1).atlas.d.new > $(3)/$(1).atlas.d.tmp
	@mv -f $(3)/$(1).atlas.d.tmp $(3)/$(1).atlas.d && rm -f $(3)/$(1).atlas.d.new
	@if cmp -s $(3)/$(1).atlas.json.new $(3)/$(1).atlas.json; then rm -f $(3)/$(1).atlas.json.new; \
	 else mv -f $(3)/$(1).atlas.json.new $(3)/$(1).atlas.json; fi
	@touch $$@

# Made by the stamp's rule; if it was deleted since, make the stamp again.
$(3)/$(1).atlas.json: $(3)/$(1).atlas.stamp
	@test -f $$@ || { rm -f $$<; $$(MAKE) --no-print-directory -f $$(firstword $$(MAKEFILE_LIST)) $$<; }

-include $(3)/$(1).atlas.d

# The store: reads the layout and the textures (listed in NAME.atlas.d).
$(3)/$(1).vts: $(3)/$(1).atlas.json $(3)/$(1).tiles.cmd
	$$(VT_TILES) --layout $(3)/$(1).atlas.json -o $$@ $$(VT_TILES_FLAGS) $$($(1)_TILES_FLAGS)

# The scene on the atlas: needs only the OBJ and the layout (not the texels).
$(3)/$(1).vt.obj $(3)/$(1).vt.mtl &: $(2) $(3)/$(1).atlas.json $(3)/$(1).offset.cmd
	$$(VT_OFFSET) $(2) $(3)/$(1).atlas.json -o $(3)/$(1).vt.obj --mtl $(3)/$(1).vt.mtl --store $(1)$(if $(4),.$(4)).vts $$(VT_OFFSET_FLAGS) $$($(1)_OFFSET_FLAGS)

# Delivery stores.
$(foreach c,$(VT_DELIVERY),$(call vt_delivery_rule,$(1),$(3),$(c),$(call vt_layers,$(1),$(c))))

# Verification stamps.
$(3)/%.vts.ok: $(3)/%.vts
	$$(VT_INFO) --verify $$(VT_INFO_FLAGS) $$<
	@touch $$@

vt_$(1)_files := $(3)/$(1).vts $(3)/$(1).vt.obj $(3)/$(1).vt.mtl \
  $(foreach c,$(VT_DELIVERY),$(3)/$(1).$(c).vts) \
  $(if $(VT_VERIFY),$(3)/$(1).vts.ok $(foreach c,$(VT_DELIVERY),$(3)/$(1).$(c).vts.ok))

.PHONY: vt-$(1)
vt-$(1): $$(vt_$(1)_files)

VT_TARGETS += vt-$(1)
VT_OUTPUTS += $$(vt_$(1)_files) $(3)/$(1).atlas.json $(3)/$(1).atlas.d $(3)/$(1).atlas.stamp \
  $(3)/$(1).atlas.json.new $(3)/$(1).atlas.d.new $(3)/$(1).atlas.d.tmp \
  $(3)/$(1).atlas.cmd $(3)/$(1).tiles.cmd $(3)/$(1).offset.cmd \
  $(foreach c,$(VT_DELIVERY),$(3)/$(1).$(c).cmd $(3)/$(1).$(c).vts.part)
endef

# $(1) NAME, $(2) OUTDIR, $(3) delivery D, $(4) its layer list (N:CODEC...; empty: D is the codec
# of every layer). With a list, vt-convert runs once per listed layer (--layer N), each step on
# the previous one's output in D.vts.part, renamed to D.vts at the end (removed on failure).
define vt_delivery_rule
$(2)/$(1).$(3).vts: $(2)/$(1).vts $(2)/$(1).$(3).cmd
$(if $(4),	@rm -f $$@.part
	trap 'rm -f $$@.part' EXIT INT TERM HUP; \
	$(foreach l,$(4),$$(VT_CONVERT) $(if $(filter $(l),$(firstword $(4))),$$<,$$@.part) -o $$@.part --layer $(word 1,$(subst :, ,$(l))) --codec $(word 2,$(subst :, ,$(l))) $$(VT_CONVERT_FLAGS) $$($(1)_CONVERT_FLAGS) &&) \
	mv -f $$@.part $$@,	$$(VT_CONVERT) $$< -o $$@ --codec $(3) $$(VT_CONVERT_FLAGS) $$($(1)_CONVERT_FLAGS) $$($(1)_$(3)_FLAGS))

endef
