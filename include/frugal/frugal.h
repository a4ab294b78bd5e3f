// frugal: an offscreen renderer on Mesa's OpenGL (EGL, OSMesa) and a CPU reference that matches
// llvmpipe bit for bit, which does only the work a scene requires and measures what each shortcut
// costs. Everything a program needs:
//
//   #include <frugal/frugal.h>
//   auto scene = frugal::loadScene("robot.glb");
//   auto renderer = frugal::Renderer::create(std::move(*scene), {.width = 800, .height = 600});
//   auto frame = renderer->render(frugal::Camera::fromScene(0), 0.0);
//   frugal::writePng("robot.png", frame->color);
#pragma once

#include <frugal/Camera.h>
#include <frugal/Files.h>
#include <frugal/Image.h>
#include <frugal/Renderer.h>
#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>
#include <frugal/Stats.h>
#include <frugal/Version.h>
