/* OpenEXR files of float32 values (files.h, sr_image_write_exr), through
 * OpenEXRCore's C API writing into softrast's safe output file. */
#define _POSIX_C_SOURCE 200809L /* fseeko */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include <openexr.h>

#include "softrast/files.h"
#include "core/error.h"
#include "output_file.h"

/* One channel is gray, "Y" (as OpenCV and most readers take a single
 * channel); three are "R", "G", "B" (x, y, z of a normal). */
static const char *const CHANNELS[2][3] = { { "Y" }, { "R", "G", "B" } };

/* OpenEXR's writes go to the output's FILE at the offset it names. */
static int64_t write_at(exr_const_context_t ctxt, void *userdata, const void *buffer, uint64_t size,
                        uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    FILE *f = userdata;
    if (fseeko(f, (off_t)offset, SEEK_SET) != 0 || fwrite(buffer, 1, size, f) != size) {
        error_cb(ctxt, EXR_ERR_WRITE_IO, "cannot write at offset %llu", (unsigned long long)offset);
        return -1;
    }
    return (int64_t)size;
}

/* The chunks of scanlines, each encoded from the interleaved values. */
static exr_result_t write_chunks(exr_context_t ctxt, const float *values, int width, int height, int channels)
{
    int32_t lines;
    exr_result_t r = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    exr_encode_pipeline_t encode = { 0 };
    bool started = false;
    for (int y = 0; r == EXR_ERR_SUCCESS && y < height; y += lines) {
        exr_chunk_info_t chunk;
        r = exr_write_scanline_chunk_info(ctxt, 0, y, &chunk);
        if (r == EXR_ERR_SUCCESS)
            r = started ? exr_encoding_update(ctxt, 0, &chunk, &encode) : exr_encoding_initialize(ctxt, 0, &chunk, &encode);
        for (int c = 0; r == EXR_ERR_SUCCESS && c < encode.channel_count; c++) {
            exr_coding_channel_info_t *ch = &encode.channels[c];
            int k = 0; /* the channels come sorted by name: find which of ours this is */
            while (k < channels && strcmp(ch->channel_name, CHANNELS[channels == 3][k]) != 0)
                k++;
            ch->user_pixel_stride = channels * (int32_t)sizeof(float);
            ch->user_line_stride = width * channels * (int32_t)sizeof(float);
            ch->user_bytes_per_element = sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->encode_from_ptr = (const uint8_t *)(values + ((size_t)chunk.start_y * (size_t)width) * (size_t)channels + k);
        }
        if (r == EXR_ERR_SUCCESS && !started)
            r = exr_encoding_choose_default_routines(ctxt, 0, &encode);
        started = started || r == EXR_ERR_SUCCESS;
        if (r == EXR_ERR_SUCCESS)
            r = exr_encoding_run(ctxt, 0, &encode);
    }
    if (started)
        exr_encoding_destroy(ctxt, &encode);
    return r;
}

bool sr_image_write_exr(const char *path, const float *values, int width, int height, int channels, sr_error *err)
{
    if (width < 1 || height < 1 || width > SR_MAX_FRAMEBUFFER_SIDE || height > SR_MAX_FRAMEBUFFER_SIDE)
        return sr_error_set(err, "%s: cannot write an image of size %dx%d", path, width, height);
    if (channels != 1 && channels != 3)
        return sr_error_set(err, "%s: an EXR of %d channels: 1 or 3", path, channels);
    sr_output o;
    if (!sr_output_open(&o, path, err))
        return false;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = o.f;
    init.write_fn = write_at;
    exr_context_t ctxt = NULL;
    int part = 0;
    exr_result_t r = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (r == EXR_ERR_SUCCESS)
        r = exr_add_part(ctxt, "depth", EXR_STORAGE_SCANLINE, &part);
    if (r == EXR_ERR_SUCCESS)
        r = exr_initialize_required_attr_simple(ctxt, part, width, height, EXR_COMPRESSION_ZIP);
    for (int c = 0; r == EXR_ERR_SUCCESS && c < channels; c++)
        r = exr_add_channel(ctxt, part, CHANNELS[channels == 3][c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (r == EXR_ERR_SUCCESS)
        r = exr_write_header(ctxt);
    if (r == EXR_ERR_SUCCESS)
        r = write_chunks(ctxt, values, width, height, channels);
    exr_result_t finished = ctxt ? exr_finish(&ctxt) : EXR_ERR_SUCCESS;
    if (r == EXR_ERR_SUCCESS)
        r = finished;
    bool written = r == EXR_ERR_SUCCESS;
    if (!written) {
        sr_error_set(err, "%s: cannot write EXR: %s", path, exr_get_default_error_message(r));
        if (!errno)
            errno = EIO;
    }
    return sr_output_close(&o, path, written, written ? err : NULL) && written;
}
