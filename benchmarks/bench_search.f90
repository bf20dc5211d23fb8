!> Contact search cost against the number of surface segments: a thin box of
!> n x n x 1 zones; its bottom face set (slave nodes) searches its top face set
!> (master segments), the margin covering the thickness so that every node finds
!> its candidates. Prints segments, test pairs, global and local search seconds
!> and ns per segment. Usage: bench_search [n ...] (default 32 100 316 1000).
program bench_search
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk
  use core_status, only: status_t
  use core_timer, only: wall_time
  use mesh_global, only: global_mesh_t, box_spec_t, mesh_make_box
  use contact_surface, only: contact_surface_t, surface_build
  use contact_search, only: bucket_search, primary_pairs, primary_pair_t
  implicit none
  integer :: sizes(8), nsize, i, n, repeat, r
  character(len=32) :: arg
  type(box_spec_t) :: spec
  type(global_mesh_t) :: mesh
  type(contact_surface_t) :: slave, master
  type(status_t) :: status
  integer, allocatable :: pairs(:, :)
  type(primary_pair_t), allocatable :: primary(:)
  real(rk) :: t0, t_global, t_local, h

  nsize = command_argument_count()
  if (nsize == 0) then
    nsize = 4
    sizes(1:4) = [32, 100, 316, 1000]
  else
    do i = 1, nsize
      call get_command_argument(i, arg)
      read(arg, *) sizes(i)
    end do
  end if
  write(output_unit, '(a)') '| segments | test pairs | global search s | local search s | '// &
      'ns per segment (global + local) |'
  write(output_unit, '(a)') '|---|---|---|---|---|'
  do i = 1, nsize
    n = sizes(i)
    h = 1.0_rk / n
    spec = box_spec_t()
    spec%nint = 1
    spec%breaks(0:1, 1) = [0.0_rk, 1.0_rk]
    spec%breaks(0:1, 2) = [0.0_rk, 1.0_rk]
    spec%breaks(0:1, 3) = [0.0_rk, 0.5_rk * h]
    spec%zones(1, :) = [n, n, 1]
    call mesh_make_box(spec, mesh, status)
    call surface_build(mesh, ['zmin'], slave, status)
    call surface_build(mesh, ['zmax'], master, status)
    if (.not. status%ok()) error stop 'bench_search: set-up failed'
    repeat = max(1, 2000000 / (n * n))
    t_global = 0.0_rk
    t_local = 0.0_rk
    do r = 1, repeat
      t0 = wall_time()
      call bucket_search(mesh%coordinates, slave, master, .false., 0.6_rk * h, pairs)
      t_global = t_global + wall_time() - t0
      t0 = wall_time()
      call primary_pairs(mesh%coordinates, master, pairs, h, h, primary)
      t_local = t_local + wall_time() - t0
    end do
    t_global = t_global / repeat
    t_local = t_local / repeat
    write(output_unit, '(a,i0,a,i0,a,es10.3,a,es10.3,a,f8.1,a)') '| ', master%nseg, ' | ', &
        size(pairs, 2), ' | ', t_global, ' | ', t_local, ' | ', &
        1.0e9_rk * (t_global + t_local) / master%nseg, ' |'
    flush(output_unit)
  end do
end program bench_search
