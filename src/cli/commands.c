#include "commands.h"

#include <stddef.h>

const cli_entry cli_commands[] = {
    {"gray", "colour to grey (= cvtColor(imread(f), BGR2GRAY))", cmd_gray},
    {"blur", "Gaussian blur (= GaussianBlur)", cmd_blur},
    {"median", "median blur 3 or 5 (= medianBlur)", cmd_median},
    {"sobel", "Sobel derivative to int16 (= Sobel(..., CV_16S, ...))", cmd_sobel},
    {"scharr", "Scharr derivative to int16 (= Scharr(..., CV_16S, ...))", cmd_scharr},
    {"laplacian", "Laplacian to int16 (= Laplacian(..., CV_16S, ksize))", cmd_laplacian},
    {"log", "Laplacian of Gaussian: blur, then Laplacian", cmd_log},
    {"canny", "Canny edges, fixed or automatic thresholds (= Canny)", cmd_canny},
    {"compare", "Sobel, LoG and Canny side by side in a captioned grid", cmd_compare},
    {"threshold", "fixed or Otsu threshold (= threshold); prints the threshold", cmd_threshold},
    {"erode", "erosion (= erode)", cmd_morphology},
    {"dilate", "dilation (= dilate)", cmd_morphology},
    {"open", "opening: erode then dilate (= morphologyEx MORPH_OPEN)", cmd_morphology},
    {"close", "closing: dilate then erode (= morphologyEx MORPH_CLOSE)", cmd_morphology},
    {"mask", "polygon region of interest (= fillPoly then bitwise_and)", cmd_mask},
    {"contours",
     "contours with area, moments, boxes, hull, defects, shape (= findContours + features)",
     cmd_contours},
    {"shapes", "shape class of each object, as a table; --overlay draws them", cmd_shapes},
    {"grasp", "grasp points: centre, approach angle, opening, jaws, score; --overlay draws them",
     cmd_grasp},
    {"lines", "standard Hough lines of the edges (= HoughLines), JSON; --overlay", cmd_lines},
    {"segments", "Hough line segments of the edges (~ HoughLinesP), JSON; --overlay", cmd_segments},
    {"circles", "Hough circles (= HoughCircles HOUGH_GRADIENT), JSON; --overlay", cmd_circles},
    {"lanes", "lane detection and tracking on an image or a sequence (JSON)", cmd_lanes},
    {NULL, NULL, NULL},
};
