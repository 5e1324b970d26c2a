// The contact sheet and the legend of a render: composed from its images once every tile is done.
#pragma once

#include <cstdint>
#include <vector>

#include "render/render.h"

namespace glint {

// The skip masks' colours: per light, light blue where tau alone skipped the pair, dark blue where
// t <= 0 did (or the light is behind the surface), grey (the reference's shading) where it was
// computed; the combined mask ramps from kSkipSomeColour (one of the pixel's lights skipped) to
// kSkipTauColour (all of them), grey where none was.
inline constexpr Rgb8 kSkipZeroColour{20, 30, 110}, kSkipTauColour{90, 170, 255},
    kSkipSomeColour{40, 62, 150};
// The combined mask's colour of a pixel whose `skipped` of `lights` lights were skipped; `grey` is
// the reference's luminance, lifted off the black of the background where every light computed.
Rgb8 combined_skip_colour(std::size_t skipped, std::size_t lights, std::uint8_t grey);

// Sets result.legend and result.contact_sheet from the result's images; error_lsb holds each
// unit's pixel errors and `object` marks the pixels that show an object (both row-major).
void compose_sheet(RenderResult& result, const std::vector<std::vector<std::uint8_t>>& error_lsb,
                   const std::vector<std::uint8_t>& object);

}  // namespace glint
