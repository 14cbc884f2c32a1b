"""Camera images to bytes: JPEG or PNG for colour images, raw float32 for depth.

Pillow's encoders are deterministic for fixed settings, so the same image always gives
the same bytes.
"""

from __future__ import annotations

import io
from enum import Enum

import numpy as np
import numpy.typing as npt
from PIL import Image

from egosim.sensors.errors import SensorConfigError


class ImageFormat(Enum):
    JPEG = "jpeg"
    PNG = "png"


def encode_image(
    pixels: npt.NDArray[np.uint8], image_format: ImageFormat, jpeg_quality: int = 90
) -> bytes:
    """An (H, W, 3) RGB image as a JPEG or PNG file's bytes."""
    if pixels.ndim != 3 or pixels.shape[2] != 3 or pixels.dtype != np.uint8:
        raise SensorConfigError(f"expected an (H, W, 3) uint8 image, got {pixels.shape}")
    buffer = io.BytesIO()
    image = Image.fromarray(pixels, mode="RGB")
    if image_format is ImageFormat.JPEG:
        # 4:4:4: thin paint lines keep their own colour instead of the asphalt's chroma.
        image.save(buffer, format="JPEG", quality=jpeg_quality, subsampling=0)
    else:
        # Level 1: labels compress well at any level; a higher one only costs time.
        image.save(buffer, format="PNG", compress_level=1)
    return buffer.getvalue()


def depth_bytes(depth: npt.NDArray[np.float32]) -> bytes:
    """(H, W) metres as little-endian float32 rows (sensor_msgs/Image 32FC1)."""
    return np.ascontiguousarray(depth, dtype="<f4").tobytes()


def encode_depth_tiff(depth: npt.NDArray[np.float32]) -> bytes:
    """(H, W) metres as a lossless 32-bit float TIFF (OpenCV reads it with IMREAD_ANYDEPTH)."""
    buffer = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(depth, dtype=np.float32), mode="F").save(
        buffer, format="TIFF"
    )
    return buffer.getvalue()
