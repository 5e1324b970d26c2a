// The page of `glint render --html`: report.html beside the images, one self-contained file (every
// PNG the render writes embedded as a data: URI, io/html.h) that opens offline in a browser: the
// key figures, the command that reproduces it, the units' table as the summary prints it, the
// skip counts and slots, every image, and the whole report.json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/html.h"
#include "render/render.h"

namespace glint {

// The page of a render report (RenderResult::to_json) and its PNGs (file name, bytes) in order.
std::string render_html(const nlohmann::json& report,
                        const std::vector<std::pair<std::string, std::string>>& pngs,
                        const HtmlRunInfo& run);

// Writes the page into `page` from the files write_render has just written into `files` (every
// .png among them, read back from its temporary, so images a render adds appear by themselves).
// Each PNG must be whole in its temporary once write_render returns; its stream is flushed here.
void write_render_html(const nlohmann::json& report, const RenderOutputs& files, OutputFile& page,
                       const HtmlRunInfo& run);

}  // namespace glint
