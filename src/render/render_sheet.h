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

// Contact-sheet tiles are the render's images reduced by this factor (at most 640 pixels wide).
int sheet_factor(int width);
// A unit's error map reduced by `factor` for the contact sheet (each block by its largest error,
// so a one-pixel error still shows; an object where any pixel of the block shows one): error_lsb
// and `object` are the render's width x height maps, row-major.
Image8 error_thumb(const std::vector<std::uint8_t>& error_lsb,
                   const std::vector<std::uint8_t>& object, int width, int height, int factor,
                   double scale);

// Sets result.legend and result.contact_sheet from the tiles, every one reduced by sheet_factor
// (so all are the same size): the reference, its specular term, the skip mask, each per-light
// mask, then each unit's image, specular term and error map (error_thumb).
void compose_sheet(RenderResult& result, std::vector<Image8> tiles);

}  // namespace glint
