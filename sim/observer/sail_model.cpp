#include "observer/sail_model.hpp"

#include <unsupported/Eigen/MatrixFunctions>

namespace sim {

Mat6 sail_a_s0(const SailParams &p)
{
    const double g = p.g_radps();
    const double two_c_om = 2.0 * p.c() * p.spin_radps;
    const double two_om_s = 2.0 * p.spin_radps * static_cast<double>(p.sigma);
    Mat6 a = Mat6::Zero();
    a(kWy, kWz) = -g;
    a(kWz, kWy) = +g;
    a(kMuY, kMuDotY) = 1.0;
    a(kMuDotY, kWz) = +two_c_om;
    a(kMuDotY, kMuDotZ) = +two_om_s;
    a(kMuZ, kMuDotZ) = 1.0;
    a(kMuDotZ, kWy) = -two_c_om;
    a(kMuDotZ, kMuDotY) = -two_om_s;
    return a;
}

Mat6 sail_a_k2(const SailParams &p)
{
    Mat6 a = Mat6::Zero();
    a(kWy, kMuY) = p.jc_kgm2 / p.j_true_kgm2();
    a(kWz, kMuZ) = p.jc_kgm2 / p.j_true_kgm2();
    a(kMuDotY, kMuY) = -p.c();
    a(kMuDotZ, kMuZ) = -p.c();
    return a;
}

Mat6 sail_a_s(const SailParams &p) { return sail_a_s0(p) + p.k2_per_s2 * sail_a_k2(p); }

Mat62 sail_b_s(const SailParams &p)
{
    const double g = p.g_radps();
    Mat62 b = Mat62::Zero();
    b(kWy, 1) = -g;
    b(kWz, 0) = +g;
    b(kMuDotY, 1) = +g;
    b(kMuDotZ, 0) = -g;
    return b;
}

Mat26 sail_momentum_rows(const SailParams &p, int rows_sigma)
{
    const double s = static_cast<double>(rows_sigma);
    const double jt = p.j_true_kgm2() + p.jc_kgm2;
    const double hr = p.h_rotor_nms();
    Mat26 m = Mat26::Zero();
    m(0, kWy) = jt;
    m(0, kMuDotY) = p.jc_kgm2;
    m(0, kMuZ) = -s * hr;
    m(1, kWz) = jt;
    m(1, kMuDotZ) = p.jc_kgm2;
    m(1, kMuY) = +s * hr;
    return m;
}

void sail_deriv(const SailParams &p, const double x[6], const double u_radps[2], double dx[6])
{
    const double g = p.g_radps();
    const double c = p.c();
    const double om = p.spin_radps;
    const double k2 = p.k2_per_s2;
    const double s = static_cast<double>(p.sigma);
    const double jcj = p.jc_kgm2 / p.j_true_kgm2();
    const double by = u_radps[0];
    const double bz = u_radps[1];
    dx[kWy] = -g * x[kWz] + jcj * k2 * x[kMuY] - g * bz;
    dx[kWz] = +g * x[kWy] + jcj * k2 * x[kMuZ] + g * by;
    dx[kMuY] = x[kMuDotY];
    dx[kMuDotY] = 2.0 * c * om * x[kWz] - c * k2 * x[kMuY] + s * 2.0 * om * x[kMuDotZ] + g * bz;
    dx[kMuZ] = x[kMuDotZ];
    dx[kMuDotZ] = -2.0 * c * om * x[kWy] - c * k2 * x[kMuZ] - s * 2.0 * om * x[kMuDotY] - g * by;
}

SailZoh sail_zoh(const SailParams &p, double h_s)
{
    Eigen::Matrix<double, 8, 8> m = Eigen::Matrix<double, 8, 8>::Zero();
    m.topLeftCorner<6, 6>() = sail_a_s(p) * h_s;
    m.topRightCorner<6, 2>() = sail_b_s(p) * h_s;
    const Eigen::Matrix<double, 8, 8> e = m.exp();
    SailZoh z;
    z.phi = e.topLeftCorner<6, 6>();
    z.gamma = e.topRightCorner<6, 2>();
    return z;
}

SailZoh sail_zoh_dk2(const SailParams &p, double h_s)
{
    using Mat8 = Eigen::Matrix<double, 8, 8>;
    Mat8 abar = Mat8::Zero();
    abar.topLeftCorner<6, 6>() = sail_a_s(p);
    abar.topRightCorner<6, 2>() = sail_b_s(p);
    Mat8 ebar = Mat8::Zero();
    ebar.topLeftCorner<6, 6>() = sail_a_k2(p);
    Eigen::Matrix<double, 16, 16> m = Eigen::Matrix<double, 16, 16>::Zero();
    m.topLeftCorner<8, 8>() = abar * h_s;
    m.topRightCorner<8, 8>() = ebar * h_s;
    m.bottomRightCorner<8, 8>() = abar * h_s;
    const Eigen::Matrix<double, 16, 16> e = m.exp();
    SailZoh d;
    d.phi = e.block<6, 6>(0, 8);
    d.gamma = e.block<6, 2>(0, 14);
    return d;
}

}  // namespace sim
