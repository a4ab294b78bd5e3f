// The library's one internal interface for the research tree (research/). The harnesses there
// time and compare the steps a frugal::Renderer chains and hides: they open stages, draw plans of
// their own, run a planner without drawing, count a backend's state changes, or draw with a minimal
// GL program beside frugal's. What they may use of src/ is what this header includes, and nothing
// else (tests/architecture checks research/'s includes); each line says what they use it for.
// Everything else they use is the public API (include/frugal/).
#pragma once

// Vocabulary: number formatting in messages and reports; medians, ranges and interquartile means.
#include "base/Format.h"
#include "base/Stats.h"

// Scenes and frames: loading with options; the transforms and View of one frame (setUpFrame); camera
// resolution; the backend interface and plans as data (and which side of the metal mix a material
// needs, for frugal info); SceneRenderer, which draws plans.
#include "pipeline/Backend.h"
#include "pipeline/Camera.h"
#include "pipeline/Frame.h"
#include "pipeline/SceneRenderer.h"
#include "scene/Load.h"

// Stages and backends: a backend with a target and a scene uploaded (Stage); opening a backend by
// kind and the memory checks; the software backend's --interp counters; GL contexts and entry
// points for the minimal GL program; the state-change cost measurement; the settings that shade a
// frame put into its parameters (applyShading, Stage.h).
#include "gl/GlApi.h"
#include "gl/GlContext.h"
#include "gl/StateCosts.h"
#include "renderer/Backends.h"
#include "renderer/Stage.h"
#include "software/SoftwareBackend.h"

// The methods, run step by step: culling (plans, cull-ahead) and its oracle; temporal
// reuse's planner and screen grid; the hidden-surface planner; draw orders on real frames and on
// state sets; paper 001's span engine.
#include "cull/CullAhead.h"
#include "cull/Culling.h"
#include "hsr/Plan.h"
#include "order/Order.h"
#include "renderer/Oracle.h"
#include "renderer/StateOrder.h"
#include "reuse/CellGrid.h"
#include "reuse/Reuse.h"
#include "span/Engine.h"
#include "span/Interp.h"

// Judging: visible sets (TOS, PVS, RVS) of a plan and of an id image.
#include "cull/VisibleSet.h"

// Files: image encoding, whole-or-nothing writes, interruption by signals.
#include "io/ImageIO.h"
#include "io/Interrupt.h"
