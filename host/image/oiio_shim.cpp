/* image/oiio_shim.cpp: the only C++ file of glpgp, built as the module
 * glpgp_oiio.so (with image/shim_glue.c) when CMake finds OpenImageIO: the
 * image read, write and writable-extension test behind glpgp_image_read,
 * glpgp_image_write and glpgp_image_path_writable (glpgp/image.h), which
 * dlopen the module on first use (image/module.c). Its one exported symbol
 * glpgp_oiio_module returns the function table of image/module.h. Every call
 * is wrapped in try/catch so no exception crosses into the C code; failures
 * are recorded with GLPGP_FAIL like everywhere else (through the host table). */
#include "module.h"

#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

using namespace OIIO;

namespace {

std::string lower_ext(const std::string &path)
{
    size_t slash = path.find_last_of('/');
    size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot);
    for (char &c : e)
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
    return e;
}

/* "dir/stem.ext" -> "dir/stem.tmp.<pid>.ext" (OpenImageIO picks the format
 * by the extension, so it must stay last). */
std::string temp_name(const std::string &path, const std::string &ext)
{
    std::string stem = path.substr(0, path.size() - ext.size());
    return stem + ".tmp." + std::to_string((long)getpid()) + ext;
}

/* While alive, file descriptor 2 points to /dev/null: the image libraries
 * (libpng's "libpng error: ..." / "libpng warning: ...") print nothing; their
 * messages reach the caller through OpenImageIO's geterror() instead. */
class QuietStderr {
  public:
    QuietStderr()
    {
        std::fflush(stderr);
        saved_ = dup(2);
        int fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved_ >= 0 && fd >= 0) dup2(fd, 2);
        if (fd >= 0) close(fd);
    }
    ~QuietStderr()
    {
        std::fflush(stderr);
        if (saved_ >= 0) {
            dup2(saved_, 2);
            close(saved_);
        }
    }
    QuietStderr(const QuietStderr &) = delete;
    QuietStderr &operator=(const QuietStderr &) = delete;

  private:
    int saved_ = -1;
};

glpgp_status read_impl(const char *path, long long max_pixels, glpgp_image **out)
{
    QuietStderr quiet;
    ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1); /* keep colour as stored */
    auto in = ImageInput::open(path, &config);
    if (!in) {
        std::string err = OIIO::geterror();
        FILE *f = std::fopen(path, "rb");
        if (!f)
            return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read image '%s': %s", path, std::strerror(errno));
        std::fclose(f);
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read image '%s': %s", path,
                          err.empty() ? "not an image format OpenImageIO reads" : err.c_str());
    }
    const ImageSpec &spec = in->spec();
    int w = spec.width, h = spec.height, nc = spec.nchannels;
    if (w <= 0 || h <= 0 || nc <= 0) {
        in->close();
        return GLPGP_FAIL(GLPGP_ERR_FORMAT, "image '%s' is empty (%d x %d, %d channels)", path, w,
                          h, nc);
    }
    /* the header is all that was read: refuse before reserving the pixels */
    if ((long long)w * (long long)h > max_pixels) {
        in->close();
        return GLPGP_FAIL(GLPGP_ERR_LIMIT,
                          "image '%s' has %d x %d = %lld pixels: more than the limit of %lld "
                          "(--max-pixels)",
                          path, w, h, (long long)w * (long long)h, max_pixels);
    }
    if (nc > 64) {
        in->close();
        return GLPGP_FAIL(GLPGP_ERR_LIMIT, "image '%s' has %d channels: more than 64", path, nc);
    }
    glpgp_image *im = nullptr;
    glpgp_status st = glpgp_image_create(w, h, nc, &im);
    if (st != GLPGP_OK) {
        in->close();
        glpgp_error_push_trace(__FILE__, __LINE__);
        return st;
    }
    im->alpha = spec.alpha_channel >= 0 && spec.alpha_channel < nc ? spec.alpha_channel : -1;
    if (!in->read_image(0, 0, 0, nc, TypeDesc::FLOAT, im->px)) {
        std::string err = in->geterror();
        in->close();
        glpgp_image_destroy(&im);
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read the pixels of '%s': %s", path, err.c_str());
    }
    in->close();
    *out = im;
    return GLPGP_OK;
}

glpgp_status write_impl(const char *path, const glpgp_image *im)
{
    QuietStderr quiet;
    std::string p(path), ext = lower_ext(p);
    if (ext.empty())
        return GLPGP_FAIL(GLPGP_ERR_ARG, "image '%s' has no file extension (.png, .exr, ...)", path);
    if (!im || !im->px || im->w <= 0 || im->h <= 0 || im->nc < 1 || im->nc > 4)
        return GLPGP_FAIL(GLPGP_ERR_ARG, "invalid image for '%s'", path);
    std::string tmp = temp_name(p, ext);
    auto out = ImageOutput::create(tmp);
    if (!out) {
        std::string err = OIIO::geterror();
        return GLPGP_FAIL(GLPGP_ERR_ARG, "cannot write images of type '%s' ('%s'): %s",
                          ext.c_str(), path, err.c_str());
    }
    int nc = im->nc;
    bool has_alpha = nc == 4 || nc == 2;
    bool drop_alpha = has_alpha && !out->supports("alpha");
    int onc = drop_alpha ? nc - 1 : nc;
    bool is_float = ext == ".exr" || ext == ".hdr" || ext == ".pfm";
    TypeDesc fmt = ext == ".exr" ? TypeDesc::HALF : is_float ? TypeDesc::FLOAT : TypeDesc::UINT8;
    ImageSpec spec(im->w, im->h, onc, fmt);
    if (has_alpha && !drop_alpha) {
        spec.alpha_channel = onc - 1;
        if (ext != ".exr") spec.attribute("oiio:UnassociatedAlpha", 1);
    }
    /* Pixels to hand over: as given, premultiplied (EXR convention), or
     * composited over white (formats without alpha). */
    size_t n = (size_t)im->w * (size_t)im->h;
    std::vector<float> buf;
    const float *data = im->px;
    if (has_alpha && (drop_alpha || ext == ".exr")) {
        buf.resize(n * (size_t)onc);
        for (size_t i = 0; i < n; i++) {
            const float *s = im->px + i * (size_t)nc;
            float a = s[nc - 1];
            float *d = buf.data() + i * (size_t)onc;
            for (int c = 0; c < nc - 1; c++) d[c] = drop_alpha ? s[c] * a + (1.0f - a) : s[c] * a;
            if (!drop_alpha) d[nc - 1] = a;
        }
        data = buf.data();
    }
    if (!out->open(tmp, spec)) {
        std::string err = out->geterror();
        std::remove(tmp.c_str());
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write image '%s': %s", path, err.c_str());
    }
    bool ok = out->write_image(TypeDesc::FLOAT, data);
    std::string err = ok ? std::string() : out->geterror();
    if (!out->close()) {
        if (ok) err = out->geterror();
        ok = false;
    }
    if (!ok) {
        std::remove(tmp.c_str());
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write image '%s': %s", path, err.c_str());
    }
    if (std::rename(tmp.c_str(), path) != 0) {
        int e = errno;
        std::remove(tmp.c_str());
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write image '%s': rename failed: %s", path,
                          std::strerror(e));
    }
    return GLPGP_OK;
}

glpgp_status image_read(const char *path, long long max_pixels, glpgp_image **out)
{
    if (!path || !out) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_image_read: NULL argument");
    *out = nullptr;
    try {
        return read_impl(path, max_pixels, out);
    } catch (const std::bad_alloc &) {
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory reading image '%s'", path);
    } catch (const std::exception &e) {
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read image '%s': %s", path, e.what());
    } catch (...) {
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot read image '%s': unknown exception", path);
    }
}

glpgp_status image_write(const char *path, const glpgp_image *im)
{
    if (!path || !*path) return GLPGP_FAIL(GLPGP_ERR_ARG, "glpgp_image_write: empty path");
    try {
        return write_impl(path, im);
    } catch (const std::bad_alloc &) {
        return GLPGP_FAIL(GLPGP_ERR_NOMEM, "out of memory writing image '%s'", path);
    } catch (const std::exception &e) {
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write image '%s': %s", path, e.what());
    } catch (...) {
        return GLPGP_FAIL(GLPGP_ERR_IO, "cannot write image '%s': unknown exception", path);
    }
}

int image_path_writable(const char *path)
{
    QuietStderr quiet;
    try {
        std::string ext = lower_ext(path ? path : "");
        if (ext.empty()) return 0;
        auto out = ImageOutput::create("x" + ext);
        if (!out) {
            (void)OIIO::geterror(); /* clear OIIO's pending error */
            return 0;
        }
        return 1;
    } catch (...) {
        return 0;
    }
}

const glpgp_oiio_api oiio_api = {GLPGP_MODULE_ABI, image_read, image_write, image_path_writable};

} // namespace

extern "C" GLPGP_MODULE_EXPORT const void *glpgp_oiio_module(const glpgp_module_host *host)
{
    return glpgp_module_glue_init(host) ? &oiio_api : nullptr;
}
